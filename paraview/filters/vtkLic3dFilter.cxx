// SPDX-License-Identifier: BSD-3-Clause
#include "vtkLic3dFilter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>

#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDataSetAttributes.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkLogger.h"
#include "vtkMatrix3x3.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#if VTK_MODULE_ENABLE_VTK_ParallelMPI
#include <mpi.h>

#include "vtkMPI.h"
#include "vtkMPICommunicator.h"
#endif

// The lic3d engine.
#include "core/enum_names.h"
#include "gpu/vulkan_context.h"
#include "lic/field_piece.h"
#include "lic/lic_reference.h"
#include "loading/session_inputs.h"
#include "render/lic_renderer.h"

// The plugin's own.
#include "device_for_rank.h"

vtkStandardNewMacro(vtkLic3dFilter);

// The device and the renderer live as long as the filter: later updates (a parameter changed in
// the GUI) reuse them.
struct vtkLic3dFilter::Engine {
  std::optional<lic3d::Context> context;
  std::optional<lic3d::LicRenderer> renderer;  // destroyed before the context
  std::string device;
  std::optional<lic3d::FieldPrecision> precision;
  std::optional<std::string> sharedDevice;  // this process's share of the node's devices

  // The selector for an empty Device property: this process's device among the node's.
  const std::string& deviceOfNode(int localRank);

  lic3d::Result<lic3d::ScalarVolume> compute(const lic3d::VectorField& field,
                                             const lic3d::NoiseVolume& noise,
                                             const lic3d::LicParams& params,
                                             const std::string& wanted,
                                             lic3d::FieldPrecision wantedPrecision,
                                             const lic3d::ProgressCallback& progress);
};

// The filter's parameters in lic3d's own structs, with their defaults.
struct vtkLic3dFilter::Parameters {
  lic3d::LicParams lic;
  lic3d::NoiseSource noise;
  lic3d::FieldPrecision precision = lic3d::FieldPrecision::Auto;
};

// Every parameter property: its name, the type ParaView sets it with, and its member of
// Parameters. Enumerations are the positions of their lic3d names (core/enum_names.h).
#define LIC3D_FILTER_PARAMETERS(X)                        \
  X(Length, int, lic.length)                              \
  X(Step, double, lic.step)                               \
  X(Bias, int, lic.bias)                                  \
  X(Integrator, int, lic.integrator)                      \
  X(Scheme, int, lic.scheme)                              \
  X(Kernel, int, lic.kernel)                              \
  X(NoiseFilter, int, lic.noiseFilter)                    \
  X(Direction, int, lic.direction)                        \
  X(NoiseSeed, int, noise.seed)                           \
  X(SparsityDistribution, int, lic.sparsity.distribution) \
  X(SparsityPoints, int, lic.sparsity.points)             \
  X(SparsityRadius, double, lic.sparsity.radius)          \
  X(SparsityRatio, double, lic.sparsity.ratio)            \
  X(SparsitySeed, int, lic.sparsity.seed)                 \
  X(FieldPrecision, int, precision)

namespace {
using Extent = std::array<int, 6>;

bool isEmpty(const Extent& e) { return e[1] < e[0] || e[3] < e[2] || e[5] < e[4]; }

lic3d::Dims dimsOf(const Extent& e) { return {e[1] - e[0] + 1, e[3] - e[2] + 1, e[5] - e[4] + 1}; }

// The input's own part: the box of its cells that are not ghosts (readers that split, and the
// GhostCellsGenerator, mark ghost cells in vtkGhostType), as a point extent. Not UPDATE_EXTENT:
// for a piece request on image data that spans every piece.
Extent ownExtent(vtkImageData* input, const Extent& extent) {
  vtkUnsignedCharArray* ghosts = input->GetCellGhostArray();
  if (!ghosts) {
    return extent;
  }
  const lic3d::Dims points = dimsOf(extent);
  const lic3d::Dims cells = glm::max(points - 1, lic3d::Dims(1));
  lic3d::Dims low(cells), high(-1);
  const unsigned char* flags = ghosts->GetPointer(0);
  for (int k = 0; k < cells.z; ++k) {
    for (int j = 0; j < cells.y; ++j) {
      const unsigned char* row = flags + lic3d::voxelIndex(cells, 0, j, k);
      for (int i = 0; i < cells.x; ++i) {
        if (row[i] & vtkDataSetAttributes::DUPLICATECELL) {
          continue;
        }
        low = glm::min(low, lic3d::Dims(i, j, k));
        high = glm::max(high, lic3d::Dims(i, j, k));
      }
    }
  }
  Extent own{0, -1, 0, -1, 0, -1};
  if (high.x < 0) {
    return own;
  }
  for (int a = 0; a < 3; ++a) {
    own[2 * a] = extent[2 * a] + low[a];
    own[2 * a + 1] = extent[2 * a] + high[a] + (points[a] > 1 ? 1 : 0);
  }
  return own;
}

// What every process contributes to the whole run: its largest |u| and whether it failed, so that
// a failing piece fails all of them instead of leaving the others waiting.
struct Shared {
  double maxVoxelSpeed = 0.0;
  bool failed = false;
};

Shared shareAcrossProcesses(Shared mine) {
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!controller || controller->GetNumberOfProcesses() <= 1) {
    return mine;
  }
  const double send[2] = {mine.maxVoxelSpeed, mine.failed ? 1.0 : 0.0};
  double receive[2] = {0.0, 0.0};
  controller->AllReduce(send, receive, 2, vtkCommunicator::MAX_OP);
  return {receive[0], receive[1] > 0.0};
}

std::string selectedArrayName(vtkInformation* info) {
  const char* name = info ? info->Get(vtkDataObject::FIELD_NAME()) : nullptr;
  return name ? name : "";
}

// No array chosen (a script that did not set Vectors before the input had data): the active point
// vectors, else the first 3-component point array, as lic3d's file readers choose.
vtkDataArray* defaultVectors(vtkImageData* input) {
  vtkPointData* points = input->GetPointData();
  if (vtkDataArray* active = points->GetVectors()) {
    return active;
  }
  for (int i = 0; i < points->GetNumberOfArrays(); ++i) {
    vtkDataArray* array = points->GetArray(i);
    if (array && array->GetNumberOfComponents() == 3) {
      return array;
    }
  }
  return nullptr;
}

// This process's rank among those of its node (MPI_COMM_TYPE_SHARED), 0 without MPI. Collective
// on the global controller's processes the first time, so the caller calls it on every process;
// it is kept for the life of the process, which never changes node.
int nodeLocalRank() {
  static const int rank = [] {
#if VTK_MODULE_ENABLE_VTK_ParallelMPI
    vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
    auto* communicator =
        controller ? vtkMPICommunicator::SafeDownCast(controller->GetCommunicator()) : nullptr;
    if (communicator && communicator->GetMPIComm() && communicator->GetMPIComm()->GetHandle()) {
      MPI_Comm node = MPI_COMM_NULL;
      MPI_Comm_split_type(*communicator->GetMPIComm()->GetHandle(), MPI_COMM_TYPE_SHARED,
                          communicator->GetLocalProcessId(), MPI_INFO_NULL, &node);
      int local = 0;
      if (node != MPI_COMM_NULL) {
        MPI_Comm_rank(node, &local);
        MPI_Comm_free(&node);
      }
      return local;
    }
#endif
    return 0;
  }();
  return rank;
}

int processCount() {
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  return controller ? controller->GetNumberOfProcesses() : 1;
}

// A property's value as the member's type; an enumeration out of range becomes its nearest name.
template <class T, class Value>
T fromProperty(Value value) {
  if constexpr (std::is_enum_v<T>) {
    const int last = static_cast<int>(lic3d::enumNames<T>().size()) - 1;
    return static_cast<T>(std::clamp(static_cast<int>(value), 0, last));
  } else {
    return static_cast<T>(value);
  }
}

// What RequestData reads of its input: the piece's extents and field, or why LIC cannot run on it.
struct InputPiece {
  Extent whole{};
  Extent extent{0, -1, 0, -1, 0, -1};
  Extent own{0, -1, 0, -1, 0, -1};  // without the input's ghost layers
  lic3d::VectorField field;
  std::size_t nonFinite = 0;
  std::string failure;  // empty when the piece can be computed
};

// Checks the parameters and the chosen `vectors` and copies them into a field on the piece's grid;
// everything that can fail before the collective step fails here, on this process only.
void readField(vtkImageData* input, vtkDataArray* vectors, const std::string& name, int association,
               const lic3d::LicParams& params, InputPiece& piece) {
  if (const lic3d::Result<void> valid = lic3d::validate(params); !valid) {
    piece.failure = valid.error().message;
    return;
  }
  if (!vectors) {
    piece.failure = name.empty() ? "3D LIC needs a 3-component point array (Vectors)"
                                 : "the input has no array '" + name + "'";
    return;
  }
  const std::string arrayName = vectors->GetName() ? vectors->GetName() : "";
  if (vectors->GetNumberOfComponents() != 3) {
    piece.failure = "the array '" + arrayName + "' has " +
                    std::to_string(vectors->GetNumberOfComponents()) +
                    " components; 3D LIC needs 3";
    return;
  }
  if (association != vtkDataObject::FIELD_ASSOCIATION_POINTS) {
    piece.failure =
        "the array '" + arrayName +
        "' is cell data: 3D LIC needs vectors at the points (apply Cell Data to Point Data)";
    return;
  }
  piece.own = ownExtent(input, piece.extent);
  lic3d::VectorField& field = piece.field;
  field.dims = dimsOf(piece.extent);
  const double* spacing = input->GetSpacing();
  const double* origin = input->GetOrigin();
  for (int a = 0; a < 3; ++a) {
    field.geometry.spacing[a] = spacing[a];
    field.geometry.origin[a] = origin[a] + piece.extent[2 * a] * spacing[a];
  }
  field.vectors.resize(lic3d::voxelCount(field.dims));
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(field.vectors.size()); ++i) {
    double v[3];
    vectors->GetTuple(i, v);
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
      ++piece.nonFinite;
      v[0] = v[1] = v[2] = 0.0;
    }
    field.vectors[static_cast<std::size_t>(i)] =
        glm::vec3(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
  }
  if (const lic3d::Result<void> spacingOk = lic3d::checkSpacing(field.geometry); !spacingOk) {
    piece.failure = spacingOk.error().message;
  }
}

// The voxels this process writes: its own part and the ghost layers asked of this filter.
Extent outputExtent(const InputPiece& piece, int askedGhosts) {
  Extent out = piece.own;
  for (int a = 0; a < 3; ++a) {
    out[2 * a] = std::max(piece.own[2 * a] - askedGhosts, piece.extent[2 * a]);
    out[2 * a + 1] = std::min(piece.own[2 * a + 1] + askedGhosts, piece.extent[2 * a + 1]);
  }
  return out;
}

// What the user should know about a piece that is computed: vectors read as zero, a direction
// matrix LIC ignores, too few ghost layers, a reader that did not split the data.
void warnAboutPiece(vtkLic3dFilter* self, vtkImageData* input, const InputPiece& piece,
                    const Extent& out, int ghostLayers) {
  if (piece.nonFinite > 0) {
    vtkWarningWithObjectMacro(self, << piece.nonFinite
                                    << " vector(s) with a NaN or infinite component were read as "
                                       "zero (streamlines stop there)");
  }
  if (vtkMatrix3x3* direction = input->GetDirectionMatrix();
      direction && !direction->IsIdentity()) {
    vtkWarningWithObjectMacro(self, << "the image's direction matrix is not the identity: LIC "
                                       "follows the vectors along the grid's index axes");
  }
  // Where the piece borders another, its ghost layers must hold the streamlines of those voxels.
  const Extent& whole = piece.whole;
  const Extent& extent = piece.extent;
  int shortest = ghostLayers;
  for (int a = 0; a < 3; ++a) {
    if (out[2 * a] > whole[2 * a]) {
      shortest = std::min(shortest, out[2 * a] - extent[2 * a]);
    }
    if (out[2 * a + 1] < whole[2 * a + 1]) {
      shortest = std::min(shortest, extent[2 * a + 1] - out[2 * a + 1]);
    }
  }
  if (shortest < ghostLayers) {
    vtkWarningWithObjectMacro(
        self, << "this piece has " << shortest << " ghost layer(s) where the streamlines need "
              << ghostLayers
              << ": voxels near its border differ from a serial run (read .vti/.pvti, or "
                 "put a GhostCellsGenerator before 3D LIC)");
  }
  if (processCount() > 1 && Extent(piece.own) == whole) {
    vtkWarningWithObjectMacro(
        self, << "this process holds the whole grid: the reader does not split its data among "
                 "processes (the legacy .vtk reader does not); convert the file to .vti to "
                 "distribute the work");
  }
}

// The output: the input's arrays passed through, cut to `out`, with LIC (the active scalars, NaN
// where sparsity hides the voxel) and |v| added.
void writeOutput(vtkImageData* input, vtkImageData* output, const InputPiece& piece,
                 const Extent& out, const lic3d::ScalarVolume& volume) {
  output->ShallowCopy(input);
  output->Crop(out.data());
  const lic3d::Dims outDims = dimsOf(out);
  const vtkIdType count = static_cast<vtkIdType>(lic3d::voxelCount(outDims));
  vtkNew<vtkFloatArray> licArray;
  licArray->SetName(std::string(lic3d::kLicArrayName).c_str());
  licArray->SetNumberOfValues(count);
  vtkNew<vtkFloatArray> magnitude;
  magnitude->SetName("Magnitude");
  magnitude->SetNumberOfValues(count);
  const Extent& extent = piece.extent;
  vtkIdType to = 0;
  for (int k = out[4]; k <= out[5]; ++k) {
    for (int j = out[2]; j <= out[3]; ++j) {
      for (int i = out[0]; i <= out[1]; ++i, ++to) {
        const std::size_t from =
            lic3d::voxelIndex(piece.field.dims, i - extent[0], j - extent[2], k - extent[4]);
        const bool drawn = volume.drawn.empty() || volume.drawn[from] != 0;
        licArray->SetValue(to, drawn ? volume.values[from] : std::nanf(""));
        magnitude->SetValue(to,
                            static_cast<float>(glm::length(glm::dvec3(piece.field.vectors[from]))));
      }
    }
  }
  output->GetPointData()->SetScalars(licArray);
  output->GetPointData()->AddArray(magnitude);
  if (out != piece.own) {
    Extent own = piece.own;  // GenerateGhostArray takes a pointer to non-const
    output->GenerateGhostArray(own.data());
  }
}

}  // namespace

#define LIC3D_DEFINE_PARAMETER(Name, Type, member)                                   \
  void vtkLic3dFilter::Set##Name(Type value) {                                       \
    auto& field = this->Params->member;                                              \
    const auto next = fromProperty<std::remove_reference_t<decltype(field)>>(value); \
    if (field != next) {                                                             \
      field = next;                                                                  \
      this->Modified();                                                              \
    }                                                                                \
  }                                                                                  \
  Type vtkLic3dFilter::Get##Name() const { return static_cast<Type>(this->Params->member); }
LIC3D_FILTER_PARAMETERS(LIC3D_DEFINE_PARAMETER)
#undef LIC3D_DEFINE_PARAMETER

vtkLic3dFilter::vtkLic3dFilter() : Gpu(new Engine), Params(new Parameters) {
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS,
                               vtkDataSetAttributes::VECTORS);
}

vtkLic3dFilter::~vtkLic3dFilter() = default;

void vtkLic3dFilter::PrintSelf(ostream& os, vtkIndent indent) {
  this->Superclass::PrintSelf(os, indent);
#define LIC3D_PRINT_PARAMETER(Name, Type, member) \
  os << indent << #Name ": " << this->Get##Name() << "\n";
  LIC3D_FILTER_PARAMETERS(LIC3D_PRINT_PARAMETER)
#undef LIC3D_PRINT_PARAMETER
  os << indent << "Device: " << this->Device << "\n"
     << indent << "CpuReference: " << this->CpuReference << "\n";
}

int vtkLic3dFilter::FillInputPortInformation(int, vtkInformation* info) {
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

int vtkLic3dFilter::RequestInformation(vtkInformation*, vtkInformationVector**,
                                       vtkInformationVector* outputVector) {
  // Whole extent, origin and spacing are the input's (copied by the executive).
  vtkDataObject::SetPointDataActiveScalarInfo(outputVector->GetInformationObject(0), VTK_FLOAT, 1);
  return 1;
}

int vtkLic3dFilter::RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector,
                                        vtkInformationVector* outputVector) {
  // Ghost layers for the streamlines of the voxels this process keeps (and for those of the
  // ghost layers asked of this filter).
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const int asked = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS());
  inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(),
              asked + lic3d::licGhostLayers(this->Params->lic));
  return 1;
}

const std::string& vtkLic3dFilter::Engine::deviceOfNode(int localRank) {
  if (!this->sharedDevice) {
    // Where listing fails, "" leaves the choice, and the error, to lic3d.
    const lic3d::Result<std::vector<lic3d::DeviceInfo>> devices = lic3d::listDevices();
    this->sharedDevice =
        devices ? lic3d::paraview::deviceSelectorForLocalRank(*devices, localRank) : "";
  }
  return *this->sharedDevice;
}

lic3d::Result<lic3d::ScalarVolume> vtkLic3dFilter::Engine::compute(
    const lic3d::VectorField& field, const lic3d::NoiseVolume& noise,
    const lic3d::LicParams& params, const std::string& wanted,
    lic3d::FieldPrecision wantedPrecision, const lic3d::ProgressCallback& progress) {
  // The device and the renderer are kept between updates unless their settings changed.
  if (!this->context || this->device != wanted || this->precision != wantedPrecision) {
    this->renderer.reset();
    this->context.reset();
    lic3d::ContextOptions options;
    options.device = wanted;
    LIC3D_TRY_ASSIGN(lic3d::Context made, lic3d::Context::create(options));
    this->context.emplace(std::move(made));
    lic3d::RendererOptions rendererOptions;
    rendererOptions.fieldPrecision = wantedPrecision;
    lic3d::Result<lic3d::LicRenderer> created =
        lic3d::LicRenderer::create(*this->context, rendererOptions);
    if (!created) {
      this->context.reset();
      return created.error();
    }
    this->renderer.emplace(std::move(*created));
    this->device = wanted;
    this->precision = wantedPrecision;
    // Which device each process took, in pvbatch's log at INFO (its default verbosity).
    vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
    const lic3d::DeviceInfo& info = this->context->deviceInfo();
    vtkLogF(INFO, "3D LIC: process %d (node-local rank %d) computes on device %d: %s (%s)",
            controller ? controller->GetLocalProcessId() : 0, nodeLocalRank(), info.index,
            info.name.c_str(), lic3d::deviceTypeName(info.type));
  }
  auto run = [&]() -> lic3d::Result<lic3d::ScalarVolume> {
    LIC3D_TRY(this->renderer->setInputs(field, noise));
    LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran, this->renderer->updateLic(params, progress));
    return this->renderer->readLicVolume();
  };
  lic3d::Result<lic3d::ScalarVolume> lic = run();
  // With LIC3D_VALIDATION=1 (the tests) the Khronos validation layer is on: any message fails.
  if (this->context->validationEnabled() && this->context->validationMessageCount() > 0) {
    const std::size_t count = this->context->validationMessageCount();
    this->context->clearValidationMessages();
    return lic3d::runtimeError(std::to_string(count) +
                               " Vulkan validation message(s), printed above");
  }
  return lic;
}

int vtkLic3dFilter::RequestData(vtkInformation*, vtkInformationVector** inputVector,
                                vtkInformationVector* outputVector) {
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  output->Initialize();

  const lic3d::LicParams& params = this->Params->lic;
  const int ghostLayers = lic3d::licGhostLayers(params);
  const int askedGhosts =
      outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS());

  InputPiece piece;
  inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), piece.whole.data());
  if (input && input->GetNumberOfPoints() > 0) {
    input->GetExtent(piece.extent.data());
  }
  const bool empty = isEmpty(piece.extent);
  if (!empty) {
    int association = vtkDataObject::FIELD_ASSOCIATION_POINTS;
    const std::string name = selectedArrayName(this->GetInputArrayInformation(0));
    vtkDataArray* vectors =
        name.empty() ? defaultVectors(input) : this->GetInputArrayToProcess(0, input, association);
    readField(input, vectors, name, association, params, piece);
  }
  lic3d::VectorField& field = piece.field;

  // Every process takes part, an empty one too: its rank on its node, which picks its device when
  // the Device property is empty, and the whole field's largest |u|.
  const int localRank = nodeLocalRank();
  const bool valid = piece.failure.empty() && !empty && !isEmpty(piece.own);
  Shared mine;
  mine.failed = !piece.failure.empty();
  mine.maxVoxelSpeed = valid ? lic3d::maxVoxelSpeedOverVoxels(field) : 0.0;
  const Shared all = shareAcrossProcesses(mine);
  if (!piece.failure.empty()) {
    vtkErrorMacro(<< piece.failure);
    return 0;
  }
  if (all.failed) {
    vtkErrorMacro(<< "3D LIC failed on another process");
    return 0;
  }
  if (!valid) {
    return 1;  // an empty piece gives an empty output
  }

  const Extent out = outputExtent(piece, askedGhosts);
  warnAboutPiece(this, input, piece, out, ghostLayers);

  const lic3d::Dims wholeDims = dimsOf(piece.whole);
  const lic3d::Dims offset(piece.extent[0] - piece.whole[0], piece.extent[2] - piece.whole[2],
                           piece.extent[4] - piece.whole[4]);
  if (field.dims != wholeDims) {
    field.piece = lic3d::FieldPiece{wholeDims, offset, all.maxVoxelSpeed};
  }
  // The whole grid's noise, cut to this piece: the pieces agree with a serial run.
  const lic3d::Result<lic3d::NoiseVolume> noise = lic3d::loadNoise(this->Params->noise, field);
  if (!noise) {
    vtkErrorMacro(<< noise.error().message);
    return 0;
  }

  const lic3d::ProgressCallback progress = [this](double f) { this->UpdateProgress(f); };
  lic3d::Result<lic3d::ScalarVolume> lic =
      this->CpuReference
          ? lic3d::computeLicReference(field, *noise, params, 0, progress)
          : this->Gpu->compute(
                field, *noise, params,
                this->Device.empty() ? this->Gpu->deviceOfNode(localRank) : this->Device,
                this->Params->precision, progress);
  if (!lic) {
    vtkErrorMacro(<< lic.error().message);
    return 0;
  }
  writeOutput(input, output, piece, out, *lic);
  return 1;
}
