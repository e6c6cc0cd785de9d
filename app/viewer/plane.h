// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The app's 2D mode (thesis chapter 3): the 2D LIC picture of the session's plane, made again
// when what it depends on changes, and copied into the window's image at the largest size that
// keeps its aspect. Unless the session gives the image's size, the picture is made at the size
// it is shown at, one image pixel per window pixel, so that the noise's grain is the screen's. A
// 2D picture takes milliseconds on a GPU, so it is made in one piece.

#include <vulkan/vulkan.h>

#include <glm/vec2.hpp>
#include <optional>

#include "core/error.h"
#include "core/session.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "jobs/plane_picture.h"

namespace lic3d::viewer {

// The 2D LIC image's size for a plane of `plane` voxels: the size the session gives
// (PlaneParams' width and height, as `lic3d render2d` makes it), else the largest that fits
// `area` (the view's width and height in pixels) keeping the plane's aspect; the plane's own
// grid while the area is unknown (0).
Dims pictureSize(Dims plane, const PlaneParams& params, glm::ivec2 area);

// The view's size the picture follows: a new size once it has stayed for `settleSeconds`, so
// that a window dragged to a new size makes one picture, not one per step of the drag. The first
// size is taken at once.
class SettledSize {
 public:
  explicit SettledSize(double settleSeconds = 0.25) : settleSeconds_(settleSeconds) {}
  // The size to make the picture at, given the view's size `now` at time `seconds`.
  glm::ivec2 update(glm::ivec2 now, double seconds);
  glm::ivec2 settled() const { return settled_; }

 private:
  double settleSeconds_;
  glm::ivec2 settled_{0};
  glm::ivec2 seen_{0};
  double seenSince_ = 0.0;
};

class PlaneView {
 public:
  // `context` must outlive the view.
  static Result<PlaneView> create(const Context& context);

  // Makes the picture of `session` (its field, plane, time, noise, LIC and grey and colour
  // parameters) for a view of `area` pixels (pictureSize) unless it already shows it. Waits for
  // the queue first when the picture is replaced (frames in flight read it). On an error the
  // previous picture stays, and the same session is not tried again (Ok at once) until it
  // changes.
  Result<void> update(const Session& session, glm::ivec2 area);
  // Whether the picture of `session` for a view of `area` pixels is shown, or could not be
  // made (the message says why).
  bool tried(const Session& session, glm::ivec2 area) const;

  // Records the picture over `target`, which holds the cleared background in
  // COLOR_ATTACHMENT_OPTIMAL and is left in TRANSFER_SRC_OPTIMAL.
  void record(VkCommandBuffer cmd, VkImage target, VkRect2D area) const;

  bool hasPicture() const { return static_cast<bool>(picture_); }
  // The picture as `lic3d render2d` writes it for `view` (with its legend), at the image's size.
  RgbaImage image(const ViewParams& view) const { return plane_.colour(view); }
  Dims fieldDims() const { return plane_.field().dims; }
  Dims imageDims() const { return plane_.imageDims(); }
  float minMagnitude() const { return plane_.minMagnitude(); }
  float maxMagnitude() const { return plane_.maxMagnitude(); }
  double licMilliseconds() const { return plane_.licMilliseconds(); }  // of the last LIC image

 private:
  // `session` with the image's size (PlaneParams' width and height) that `area` asks for.
  Session sized(const Session& session, glm::ivec2 area) const;
  Result<void> make(const Session& session, glm::ivec2 area);

  const Context* context_ = nullptr;
  PlanePicture plane_;
  Image picture_;                  // RGBA8, kept in TRANSFER_SRC_OPTIMAL
  std::optional<Session> made_;    // what picture_ shows
  std::optional<Session> failed_;  // the last session whose picture could not be made
};

}  // namespace lic3d::viewer
