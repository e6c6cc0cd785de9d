// SPDX-License-Identifier: BSD-3-Clause
// The "3D LIC" filter: Line Integral Convolution of a 3-component point array of image data,
// computed by the lic3d engine on a Vulkan device (Mesa's lavapipe where there is no GPU).
//
// Under MPI (`mpirun -np N pvbatch --mpi`) each process computes its piece: it asks its input for
// enough ghost layers to hold every streamline of its own voxels (lic3d::licGhostLayers), takes
// the largest |v| of the whole field from all processes, and makes noise and sparsity mask from
// indices in the whole grid, so the pieces together are the serial result (docs/PARAVIEW.md).
//
// Output: image data on the input's own (non-ghost) extent with the input's point and cell
// arrays passed through, and the point arrays "LIC" (the active scalars: float in [0,1], NaN where
// sparsity hides the voxel) and "Magnitude" (|v| of the input vectors) added.
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

  // The parameters, stored in the engine's own structs (lic3d::LicParams, lic3d::NoiseSource),
  // which give their defaults; Lic3dFilter.xml repeats those for ParaView's panel, and a test
  // (tests/test_paraview_xml.cpp) holds the two together. `lic3d render --help` describes each.
  // Enumerations are their lic3d names' positions: integrator 0 euler, 1 rk2, 2 rk4; scheme
  // 0 exact, 1 ab2, 2 fused; kernel 0 box, 1 hann, 2 gauss; noise filter 0 nearest, 1 linear;
  // direction 0 normalized, 1 magnitude; sparsity 0 none, 1 checkerboard, 2 poisson, 3
  // poisson-approx, 4 jitter, 5 halton, 6 hammersley; field precision 0 auto, 1 half, 2 float, 3
  // byte.
  void SetLength(int value);
  int GetLength() const;
  void SetStep(double value);
  double GetStep() const;
  void SetBias(int value);
  int GetBias() const;
  void SetIntegrator(int value);
  int GetIntegrator() const;
  void SetScheme(int value);
  int GetScheme() const;
  void SetKernel(int value);
  int GetKernel() const;
  void SetNoiseFilter(int value);
  int GetNoiseFilter() const;
  void SetDirection(int value);
  int GetDirection() const;
  void SetNoiseSeed(int value);
  int GetNoiseSeed() const;
  void SetSparsityDistribution(int value);
  int GetSparsityDistribution() const;
  void SetSparsityPoints(int value);
  int GetSparsityPoints() const;
  void SetSparsityRadius(double value);
  double GetSparsityRadius() const;
  void SetSparsityRatio(double value);
  double GetSparsityRatio() const;
  void SetSparsitySeed(int value);
  int GetSparsitySeed() const;
  void SetFieldPrecision(int value);
  int GetFieldPrecision() const;

  // The device: an index of `lic3d devices` or part of a device name, the same on every process;
  // "" for lic3d's choice: the usable devices of the best kind (discrete GPU, integrated, virtual,
  // CPU) shared out among the processes of a node by node-local rank (device_for_rank.h).
  vtkSetStdStringFromCharMacro(Device);
  vtkGetCharFromStdStringMacro(Device);
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

  std::string Device;
  bool CpuReference = false;

 private:
  vtkLic3dFilter(const vtkLic3dFilter&) = delete;
  void operator=(const vtkLic3dFilter&) = delete;

  struct Engine;
  std::unique_ptr<Engine> Gpu;
  struct Parameters;  // lic3d's parameter structs
  std::unique_ptr<Parameters> Params;
};

#endif
