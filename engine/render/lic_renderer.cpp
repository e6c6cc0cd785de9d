// SPDX-License-Identifier: BSD-3-Clause
#include "render/lic_renderer.h"

#include <vector>

#include "core/colormap.h"
#include "core/stage_times.h"
#include "gpu/submit.h"
#include "lic/annotation.h"

namespace lic3d {

Result<LicRenderer> LicRenderer::create(const Context& context, const RendererOptions& options) {
  const StageTimer timer("pipelines");
  LicRenderer renderer;
  renderer.context_ = &context;
  renderer.textures_ = FieldTextures(context, options.fieldPrecision, options.naiveLicKernel);
  LIC3D_TRY_ASSIGN(renderer.target_, OffscreenTarget::create(context, options.framePrecision));
  LIC3D_TRY_ASSIGN(
      renderer.job_,
      LicVolumeJob::create(context, options.doubleBuffered, options.naiveLicKernel,
                           options.licLaunch, options.visibleWork, options.visibleFullPassShare));
  LIC3D_TRY_ASSIGN(renderer.slicePass_, SlicePass::create(context, options.runtimeModes));
  return renderer;
}

LicRenderer::~LicRenderer() {
  // Frames recorded by the caller may still use the volumes.
  if (context_) vkDeviceWaitIdle(context_->device());
}

// ---- Inputs ------------------------------------------------------------------------------------

Result<void> LicRenderer::replaceField(Dims dims, const std::optional<FieldPiece>& piece) {
  // In-flight frames may still read the old texture and volumes.
  vkDeviceWaitIdle(context_->device());
  job_.dropField(dims != textures_.field().dims, piece);
  return textures_.dropField(dims);
}

Result<void> LicRenderer::setInputs(const VectorField& field, const NoiseVolume& noise) {
  LIC3D_TRY(replaceField(field.dims, field.piece));
  return textures_.setInputs(field, noise);
}

Result<void> LicRenderer::setAnalyticInputs(const AnalyticInputs& inputs) {
  if (textures_.keepsSeparateNoise())
    return unsupportedError(
        "the naive kernel reads the noise from a texture of its own: set the "
        "field and noise from the host");
  std::optional<FieldPiece> piece;
  if (inputs.isBrick()) piece = FieldPiece{.wholeDims = inputs.dims, .offset = inputs.brickOffset};
  LIC3D_TRY(replaceField(inputs.texelDims(), piece));
  return textures_.setAnalyticInputs(inputs);
}

Result<void> LicRenderer::setScalars(const PointScalars* color, const PointScalars* opacity) {
  vkDeviceWaitIdle(context_->device());  // in-flight frames may sample the old texture
  return textures_.setScalars(color, opacity);
}

Result<void> LicRenderer::setLicVolume(const ScalarVolume& volume, const LicParams& params) {
  return job_.setVolume(volume, params, textures_);
}

Result<void> LicRenderer::blendTime(int first, int second, double weight) {
  LIC3D_TRY_ASSIGN(const std::optional<Dims> grid, textures_.blendGrid(first, second, weight));
  if (grid) {
    // A texture of the steps' grid replaces the field's; frames in flight may read the old one.
    vkDeviceWaitIdle(context_->device());
    if (*grid != textures_.field().dims) {
      job_.dropField(true, std::nullopt);
    } else {
      job_.forgetPiece();
    }
  }
  LIC3D_TRY_ASSIGN(const bool blended, textures_.blendTime(first, second, weight));
  if (blended) job_.markFieldChanged();
  return {};
}

Result<bool> LicRenderer::updateLic(const LicParams& params, const ProgressCallback& progress) {
  return job_.update(params, textures_, progress);
}

Result<bool> LicRenderer::updateLic(const LicParams& params, const ViewParams& view,
                                    const ProgressCallback& progress) {
  LIC3D_TRY_ASSIGN(const std::optional<VisibleBricksSetup> visible, visibleBricksFor(view));
  return job_.update(params, textures_, progress, visible ? &*visible : nullptr);
}

Result<bool> LicRenderer::needsLic(const LicParams& params, const ViewParams& view) const {
  LIC3D_TRY_ASSIGN(const std::optional<VisibleBricksSetup> visible, visibleBricksFor(view));
  return visible ? job_.needs(params, *visible) : job_.needs(params);
}

Result<std::optional<VisibleBricksSetup>> LicRenderer::visibleBricksFor(
    const ViewParams& given) const {
  const FieldTexture& field = textures_.field();
  if (!job_.visibleWork() || !field.image) return std::optional<VisibleBricksSetup>();
  LIC3D_TRY(validate(given));
  // The slices as drawn (shownDraws), in the picture's part of the frame (recordFrame).
  const ViewParams view = shownView(given, volumeFacts().transfer());
  const glm::ivec4 p = pictureLayoutFor(given).picture;
  const VkRect2D area{{p.x, p.y},
                      {static_cast<std::uint32_t>(p.z), static_cast<std::uint32_t>(p.w)}};
  const std::vector<std::uint8_t> table = colormapTable(view.transfer, view.colormap);
  std::optional<VisibleBricksSetup> visible;
  for (const EyeDraw& draw : eyeDraws(area, view)) {
    const VisibleBricksSetup eye = visibleBricksSetup(draw.frame, field.dims, table);
    visible = visible ? unionOf(*visible, eye) : eye;
  }
  return visible;
}

// ---- Drawing -----------------------------------------------------------------------------------

VolumeFacts LicRenderer::volumeFacts() const {
  const FieldTexture& field = textures_.field();
  const ScalarTexture& scalars = textures_.scalars();
  const IntensityStatistics& statistics = job_.statistics();
  VolumeFacts facts;
  facts.dims = field.dims;
  facts.geometry = field.geometry;
  facts.minMagnitude = static_cast<float>(field.minMagnitude);
  facts.maxMagnitude = static_cast<float>(field.maxMagnitude);
  facts.texelToPhysical = glm::vec3(field.texelToPhysical);
  facts.fieldPrecision = field.precision;
  facts.intensityMean = statistics.mean;
  facts.intensityDeviation = statistics.deviation;
  facts.intensities = statistics.histogram;
  facts.colorValues = field.speeds;
  facts.opacityValues = field.speeds;
  facts.colorScalar = scalars.color;
  facts.opacityScalar = scalars.opacity;
  facts.scalarRange = scalars.range;
  facts.colorUnit = field.unit;
  if (scalars.color) {
    facts.colorValues = scalars.colorValues;
    facts.minMagnitude = static_cast<float>(scalars.colorValues->min);
    facts.maxMagnitude = static_cast<float>(scalars.colorValues->max);
    facts.colorName = scalars.colorName;
    facts.colorUnit = scalars.colorUnit;
  }
  if (scalars.opacity) facts.opacityValues = scalars.opacityValues;
  const std::size_t voxels = voxelCount(field.dims);
  facts.drawnFraction =
      statistics.histogram && voxels > 0
          ? static_cast<float>(static_cast<double>(statistics.voxels) / static_cast<double>(voxels))
          : 1.0f;
  const std::optional<LicParams>& shown = job_.shownParams();
  facts.sparsity = shown && shown->sparsity.distribution != SparsityDistribution::None;
  return facts;
}

std::vector<LicRenderer::EyeDraw> LicRenderer::eyeDraws(VkRect2D area,
                                                        const ViewParams& view) const {
  const VolumeFacts facts = volumeFacts();
  const bool sideBySide = view.stereo == StereoMode::SideBySide;
  const VkExtent2D eyeExtent{sideBySide ? area.extent.width / 2 : area.extent.width,
                             area.extent.height};
  const VkOffset2D at = area.offset;
  const VkOffset2D right{at.x + static_cast<std::int32_t>(eyeExtent.width), at.y};
  const auto draw = [&](Eye eye, VkOffset2D offset) {
    return EyeDraw{makeSliceFrame(view, facts, eye, eyeExtent), {offset, eyeExtent}};
  };
  switch (view.stereo) {
    case StereoMode::None: return {draw(Eye::Mono, at)};
    case StereoMode::Anaglyph: return {draw(Eye::Left, at), draw(Eye::Right, at)};
    case StereoMode::SideBySide: return {draw(Eye::Left, at), draw(Eye::Right, right)};
  }
  return {};
}

Result<std::vector<LicRenderer::EyeDraw>> LicRenderer::shownDraws(VkRect2D area,
                                                                  const ViewParams& given) {
  LIC3D_TRY(validate(given));
  // A signed scalar's diverging map and its opacity by size (core/view_params.h).
  const ViewParams view = shownView(given, volumeFacts().transfer());
  LIC3D_TRY(slicePass_.setTransferFunction(view.transfer, view.colormap));
  return eyeDraws(area, view);
}

Result<void> LicRenderer::prepareDraw(VkCommandBuffer cmd, VkRect2D area, const ViewParams& given,
                                      std::uint32_t slotBase) {
  if (!hasVolume()) return {};
  LIC3D_TRY_ASSIGN(const std::vector<EyeDraw> draws, shownDraws(area, given));
  for (std::uint32_t i = 0; i < draws.size(); ++i)
    LIC3D_TRY(slicePass_.prepare(cmd, draws[i].viewport, job_.shownVolume(), textures_.field(),
                                 textures_.scalars().image, draws[i].frame, slotBase + i));
  return {};
}

Result<void> LicRenderer::recordDraw(VkCommandBuffer cmd, VkFormat format, VkRect2D area,
                                     const ViewParams& given, std::uint32_t slotBase) {
  if (!hasVolume()) return {};
  LIC3D_TRY_ASSIGN(const std::vector<EyeDraw> draws, shownDraws(area, given));
  for (std::uint32_t i = 0; i < draws.size(); ++i)
    LIC3D_TRY(slicePass_.record(cmd, format, draws[i].viewport, job_.shownVolume(),
                                textures_.field(), textures_.scalars().image, draws[i].frame,
                                slotBase + i));
  return {};
}

Result<void> LicRenderer::recordFrame(VkCommandBuffer cmd, const OffscreenTarget& target,
                                      const ViewParams& view) {
  const glm::ivec4 p = pictureLayoutFor(view).picture;
  const VkRect2D area{{p.x, p.y},
                      {static_cast<std::uint32_t>(p.z), static_cast<std::uint32_t>(p.w)}};
  // The frame is begun and ended whatever fails, so the read-back that follows finds it.
  Result<void> status = prepareDraw(cmd, area, view, 0);
  target.beginFrame(cmd, view.background);
  if (status) status = recordDraw(cmd, target.format(), area, view, 0);
  vkCmdEndRendering(cmd);
  return status;
}

Result<RgbaImage> LicRenderer::render(const LicParams& params, const ViewParams& view) {
  LIC3D_TRY(validate(view));
  LIC3D_TRY_ASSIGN([[maybe_unused]] const bool recomputed, updateLic(params, view));
  const int width = view.stereo == StereoMode::SideBySide ? 2 * view.width : view.width;
  LIC3D_TRY(target_.resize(width, view.height));
  Result<void> status;
  StageTimer drawing("frame");
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        status = recordFrame(cmd, target_, view);
        target_.recordReadback(cmd);
      },
      "render frame"));
  LIC3D_TRY(std::move(status));
  drawing.stop();

  StageTimer reading("frame read-back");
  RgbaImage image = target_.read();
  reading.stop();
  const StageTimer annotating("annotation");
  const std::optional<LegendSpec> legend = legendFor(view);
  annotatePicture(image, view, legend ? &*legend : nullptr, textures_.field().dims,
                  textures_.field().geometry);
  return image;
}

std::optional<LegendSpec> LicRenderer::legendFor(const ViewParams& view) const {
  if (!view.legend || view.color != ColorMode::Magnitude) return std::nullopt;
  const VolumeFacts facts = volumeFacts();
  return viewLegend(view, facts.transfer(), facts.colorName, facts.colorUnit);
}

PictureLayout LicRenderer::pictureLayoutFor(const ViewParams& view) const {
  const std::optional<LegendSpec> legend = legendFor(view);
  return viewLayout(view, legend ? &*legend : nullptr);
}

}  // namespace lic3d
