// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The app's 2D mode (thesis chapter 3): the 2D LIC picture of the session's plane, made again
// when what it depends on changes, and copied into the window's image at the largest size that
// keeps its aspect. A 2D picture takes milliseconds on a GPU, so it is made in one piece.

#include <vulkan/vulkan.h>

#include <optional>

#include "core/error.h"
#include "core/session.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "jobs/plane_picture.h"

namespace lic3d::viewer {

class PlaneView {
 public:
  // `context` must outlive the view.
  static Result<PlaneView> create(const Context& context);

  // Makes the picture of `session` (its field, plane, time, noise, LIC and grey and colour
  // parameters) unless it already shows it. Waits for the queue first when the picture is
  // replaced (frames in flight read it). On an error the previous picture stays, and the same
  // session is not tried again (Ok at once) until it changes.
  Result<void> update(const Session& session);

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
  Result<void> make(const Session& session);

  const Context* context_ = nullptr;
  PlanePicture plane_;
  Image picture_;                  // RGBA8, kept in TRANSFER_SRC_OPTIMAL
  std::optional<Session> made_;    // what picture_ shows
  std::optional<Session> failed_;  // the last session whose picture could not be made
};

}  // namespace lic3d::viewer
