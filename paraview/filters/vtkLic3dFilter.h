// The "3D LIC" filter: Line Integral Convolution of a 3-component point array of image data,
// computed by the lic3d engine on a Vulkan device (Mesa's lavapipe where there is no GPU).
//
// Under MPI (`mpirun -np N pvbatch --mpi`) each process computes its piece: it asks its input for
// enough ghost layers to hold every streamline of its own voxels (lic3d::licGhostLayers), takes
// the largest |v| of the whole field from all processes, and makes noise and sparsity mask from
// indices in the whole grid, so the pieces together are the serial result (docs/PARAVIEW.md).
//
// Output: image data on the input's own (non-ghost) extent with the point arrays "LIC" (float in
// [0,1], NaN where sparsity hides the voxel) and "Magnitude" (|v| of the input vectors).
#ifndef vtkLic3dFilter_h
#define vtkLic3dFilter_h

#include <memory>
#include <string>

#include "Lic3dFiltersModule.h"
#include "vtkImageAlgorithm.h"

class LIC3DFILTERS_EXPORT vtkLic3dFilter : public vtkImageAlgorithm {
 public:
  static vtkLic3dFilter* New();
  vtkTypeMacro(vtkLic3dFilter, vtkImageAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  // The LIC parameters (lic3d::LicParams; `lic3d render --help` describes each).
  vtkSetMacro(Length, int);
  vtkGetMacro(Length, int);
  vtkSetMacro(Step, double);
  vtkGetMacro(Step, double);
  vtkSetMacro(Bias, int);
  vtkGetMacro(Bias, int);
  vtkSetMacro(Integrator, int);  // 0 euler, 1 rk2, 2 rk4
  vtkGetMacro(Integrator, int);
  vtkSetMacro(Scheme, int);  // 0 exact, 1 ab2 (rk2 only)
  vtkGetMacro(Scheme, int);
  vtkSetMacro(Kernel, int);  // 0 box, 1 hann, 2 gauss
  vtkGetMacro(Kernel, int);
  vtkSetMacro(NoiseFilter, int);  // 0 nearest, 1 linear
  vtkGetMacro(NoiseFilter, int);
  vtkSetMacro(Direction, int);  // 0 normalized, 1 magnitude
  vtkGetMacro(Direction, int);
  vtkSetMacro(NoiseSeed, int);
  vtkGetMacro(NoiseSeed, int);

  // Sparsity (lic3d::SparsityParams): 0 none, 1 checkerboard, 2 poisson, 3 poisson-approx,
  // 4 jitter, 5 halton, 6 hammersley.
  vtkSetMacro(SparsityDistribution, int);
  vtkGetMacro(SparsityDistribution, int);
  vtkSetMacro(SparsityPoints, int);
  vtkGetMacro(SparsityPoints, int);
  vtkSetMacro(SparsityRadius, double);
  vtkGetMacro(SparsityRadius, double);
  vtkSetMacro(SparsityRatio, double);
  vtkGetMacro(SparsityRatio, double);
  vtkSetMacro(SparsitySeed, int);
  vtkGetMacro(SparsitySeed, int);

  // The device: "" for lic3d's choice (discrete GPU, integrated, virtual, CPU), an index of
  // `lic3d devices`, or part of a device name.
  vtkSetStdStringFromCharMacro(Device);
  vtkGetCharFromStdStringMacro(Device);
  // Field texture precision: 0 auto, 1 half, 2 float.
  vtkSetMacro(FieldPrecision, int);
  vtkGetMacro(FieldPrecision, int);
  // Compute with lic3d's CPU reference (double precision, every hardware thread) instead of the
  // device: slow, but the same numbers on every piece up to rounding, which the tests use.
  vtkSetMacro(CpuReference, bool);
  vtkGetMacro(CpuReference, bool);

 protected:
  vtkLic3dFilter();
  ~vtkLic3dFilter() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestInformation(vtkInformation* request, vtkInformationVector** inputVector,
                         vtkInformationVector* outputVector) override;
  int RequestUpdateExtent(vtkInformation* request, vtkInformationVector** inputVector,
                          vtkInformationVector* outputVector) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
                  vtkInformationVector* outputVector) override;

  int Length = 20;
  double Step = 0.5;
  int Bias = 0;
  int Integrator = 1;
  int Scheme = 0;
  int Kernel = 0;
  int NoiseFilter = 1;
  int Direction = 0;
  int NoiseSeed = 1;
  int SparsityDistribution = 0;
  int SparsityPoints = 0;
  double SparsityRadius = 0.0;
  double SparsityRatio = 0.05;
  int SparsitySeed = 1;
  std::string Device;
  int FieldPrecision = 0;
  bool CpuReference = false;

 private:
  vtkLic3dFilter(const vtkLic3dFilter&) = delete;
  void operator=(const vtkLic3dFilter&) = delete;

  struct Engine;
  std::unique_ptr<Engine> Gpu;
};

#endif
