// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/plane.h"

#include <algorithm>
#include <cmath>

#include "gpu/submit.h"
#include "lic/lic2d_reference.h"
#include "loading/plane_inputs.h"

namespace lic3d::viewer {
namespace {

// The picture shows all of these (PlanePicture makes again only what changed).
bool samePicture(const Session& a, const Session& b) {
  return a.field == b.field && a.plane == b.plane && a.time == b.time && a.noise == b.noise &&
         a.precision == b.precision && a.lic == b.lic && a.view == b.view;
}

}  // namespace

Dims pictureSize(Dims plane, const PlaneParams& params, glm::ivec2 area) {
  if (params.width > 0 || params.height > 0 || area.x <= 0 || area.y <= 0 || plane.x <= 0 ||
      plane.y <= 0)
    return imageSize(plane, params);
  const double scale =
      std::min(static_cast<double>(area.x) / plane.x, static_cast<double>(area.y) / plane.y);
  return {std::clamp(static_cast<int>(std::lround(plane.x * scale)), 1, area.x),
          std::clamp(static_cast<int>(std::lround(plane.y * scale)), 1, area.y), 1};
}

glm::ivec2 SettledSize::update(glm::ivec2 now, double seconds) {
  if (settled_ == glm::ivec2(0)) settled_ = now;
  if (now != seen_) {
    seen_ = now;
    seenSince_ = seconds;
  }
  if (now != settled_ && seconds - seenSince_ >= settleSeconds_) settled_ = now;
  return settled_;
}

Result<PlaneView> PlaneView::create(const Context& context) {
  PlaneView view;
  view.context_ = &context;
  LIC3D_TRY(view.plane_.useGpu(context));
  return view;
}

Session PlaneView::sized(const Session& session, glm::ivec2 area) const {
  Session s = session;
  const Dims size = pictureSize(plane_.field().dims, session.plane, area);
  s.plane.width = size.x;
  s.plane.height = size.y;
  return s;
}

bool PlaneView::tried(const Session& session, glm::ivec2 area) const {
  const Session wanted = sized(session, area);
  return (made_ && samePicture(*made_, wanted)) || (failed_ && samePicture(*failed_, wanted));
}

Result<void> PlaneView::update(const Session& session, glm::ivec2 area) {
  const Session wanted = sized(session, area);
  if (made_ && samePicture(*made_, wanted)) return {};
  // A picture that could not be made is tried again only once the session changes, not every
  // frame (a field file that cannot be read would be read at each).
  if (failed_ && samePicture(*failed_, wanted)) return {};
  Result<void> made = make(session, area);
  if (made)
    failed_.reset();
  else
    failed_ = wanted;
  return made;
}

Result<void> PlaneView::make(const Session& session, glm::ivec2 area) {
  LIC3D_TRY(checkLic2DParams(session.lic));
  // The size fitting the view follows the plane's aspect, known once the plane is made: a new
  // field or plane is sized a second time (only the noise is made again).
  Session s = sized(session, area);
  const Dims before = plane_.field().dims;
  LIC3D_TRY(plane_.setInputs(s));
  if (plane_.field().dims != before) {
    s = sized(session, area);
    LIC3D_TRY(plane_.setInputs(s));
  }
  LIC3D_TRY(plane_.computeLic(s.lic));
  // The app draws its own legend over the window.
  ViewParams view = s.view;
  view.legend = false;
  const RgbaImage rgba = plane_.colour(view);

  vkQueueWaitIdle(context_->queue());  // frames in flight read the old picture
  picture_ = Image();
  ImageDesc desc;
  desc.type = VK_IMAGE_TYPE_2D;
  desc.format = VK_FORMAT_R8G8B8A8_UNORM;
  desc.extent = {static_cast<std::uint32_t>(rgba.width), static_cast<std::uint32_t>(rgba.height),
                 1};
  desc.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
               VK_IMAGE_USAGE_SAMPLED_BIT;
  desc.name = "2d lic picture";
  LIC3D_TRY_ASSIGN(picture_, Image::create(*context_, desc));
  LIC3D_TRY(uploadImage(*context_, picture_, rgba.pixels.data(), rgba.pixels.size()));
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        imageBarrier(cmd, picture_.handle(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                     VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
      },
      "2d lic picture layout"));
  made_ = s;
  return {};
}

void PlaneView::record(VkCommandBuffer cmd, VkImage target, VkRect2D area) const {
  imageBarrier(
      cmd, target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
      VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
      VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  if (picture_) {
    const VkExtent3D size = picture_.extent();
    const VkExtent2D extent = area.extent;
    const double scale = std::min(static_cast<double>(extent.width) / size.width,
                                  static_cast<double>(extent.height) / size.height);
    const int width = std::max(1, static_cast<int>(size.width * scale));
    const int height = std::max(1, static_cast<int>(size.height * scale));
    const int x0 = area.offset.x + (static_cast<int>(extent.width) - width) / 2;
    const int y0 = area.offset.y + (static_cast<int>(extent.height) - height) / 2;
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {static_cast<std::int32_t>(size.width),
                          static_cast<std::int32_t>(size.height), 1};
    blit.dstSubresource = blit.srcSubresource;
    blit.dstOffsets[0] = {x0, y0, 0};
    blit.dstOffsets[1] = {x0 + width, y0 + height, 1};
    vkCmdBlitImage(cmd, picture_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
  }
  imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_BLIT_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
               VK_ACCESS_2_TRANSFER_READ_BIT);
}

}  // namespace lic3d::viewer
