// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/soak.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "options/session_options.h"

namespace lic3d::viewer {
namespace {

constexpr std::uint64_t kChangeEvery = 10;
constexpr std::uint64_t kResizeEvery = 250;
constexpr std::uint64_t kSampleEvery = 50;
constexpr std::uint64_t kWarmupFrames = 100;
constexpr std::uint64_t kRssSlack = 8u << 20;

// Resident set size of this process, from /proc/self/statm.
std::uint64_t residentBytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  unsigned long long size = 0, resident = 0;
  const int n = std::fscanf(f, "%llu %llu", &size, &resident);
  std::fclose(f);
  return n == 2 ? resident * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE)) : 0;
}

}  // namespace

// A parameter change every kChangeEvery frames, alternately of the LIC and of the view (redraw).
// The LIC changes take turns among everything the app recomputes asynchronously: the length
// (LIC slabs over frames), sparsity (the mask on a worker thread), the noise seed (field and
// noise read again on the loading thread) and, for an unsteady field, the time (steps read on a
// worker thread and blended on the GPU). Each is set and undone in turn.
void Soak::step(std::uint64_t frame, int frames, Session& session, const AppState& state,
                const std::function<void(bool larger)>& resize) {
  if (frames <= 0 || frame >= static_cast<std::uint64_t>(frames)) return;
  if (!base_) base_ = session;
  const Session& base = *base_;
  const std::uint64_t n = frame;
  if (n > 0 && n % kChangeEvery == 0) {
    if ((n / kChangeEvery) % 2 == 1) {
      switch ((n / (2 * kChangeEvery)) % 4) {
        case 0:
          session.lic.length =
              session.lic.length == base.lic.length ? base.lic.length + 1 : base.lic.length;
          break;
        case 1:
          if (session.lic.sparsity == base.lic.sparsity) {
            // A new seed each time: the mask is made again, not taken from the last one.
            session.lic.sparsity = SparsityParams{};
            session.lic.sparsity.distribution = SparsityDistribution::Poisson;
            session.lic.sparsity.seed = ++counts.masks;
          } else {
            session.lic.sparsity = base.lic.sparsity;
          }
          break;
        case 2:
          session.noise.seed =
              session.noise.seed == base.noise.seed ? base.noise.seed + 1 : base.noise.seed;
          break;
        default:
          // Two and a half steps on: neither step of the bracket is resident.
          if (state.seriesStep > 0.0)
            session.time =
                session.time == base.time ? base.time + 2.5 * state.seriesStep : base.time;
          break;
      }
    } else {
      session.view.camera.azimuth = std::fmod(session.view.camera.azimuth + 7.0f, 360.0f);
    }
  }
  // A resize every kResizeEvery frames, undone 10 frames later: both recreate the swapchain, and
  // the memory samples (multiples of 50) all see the window at its own size.
  if (n > 0 && (n % kResizeEvery == 0 || n % kResizeEvery == 10)) resize(n % kResizeEvery == 0);
  // Memory is sampled at rest: the first frame from each multiple of kSampleEvery on at which
  // nothing is being read, masked or recomputed (work in flight holds old and new at once).
  if (n % kSampleEvery == 0) sampleDue_ = true;
  if (sampleDue_ && state.atRest) {
    samples_.push_back({n, residentBytes(), state.deviceBytes});
    sampleDue_ = false;
  }
}

// After the warm-up, memory must not grow: the largest sample of the second half may exceed the
// largest of the first half by kRssSlack of RSS (allocator and driver caches) and not at all in
// device memory (the allocator's own count).
int Soak::verdict(std::uint64_t frames, int swapchains, std::uint64_t masksBuilt) const {
  std::vector<MemorySample> s;
  for (const MemorySample& m : samples_)
    if (m.frame >= kWarmupFrames) s.push_back(m);
  if (s.size() < 4) {
    std::fprintf(stderr, "lic3d-view: error: --soak needs --frames of at least %d\n",
                 static_cast<int>(kWarmupFrames + 4 * kSampleEvery));
    return cli::kExitBadInput;
  }
  const std::size_t half = s.size() / 2;
  auto maxOf = [&](std::size_t from, std::size_t to, auto member) {
    std::uint64_t m = 0;
    for (std::size_t i = from; i < to; ++i) m = std::max(m, s[i].*member);
    return m;
  };
  const std::uint64_t rss1 = maxOf(0, half, &MemorySample::rssBytes);
  const std::uint64_t rss2 = maxOf(half, s.size(), &MemorySample::rssBytes);
  const std::uint64_t dev1 = maxOf(0, half, &MemorySample::deviceBytes);
  const std::uint64_t dev2 = maxOf(half, s.size(), &MemorySample::deviceBytes);
  const double mib = 1.0 / (1 << 20);
  std::printf(
      "lic3d-view soak: %llu frames, samples every %d after %d warm-up frames; RSS max "
      "%.1f MiB (first half) -> %.1f MiB (second half); device memory max %.1f -> %.1f MiB; "
      "%d swapchains; %llu LIC volumes, %llu of %llu sparsity masks, %llu field reads, "
      "%llu time steps read\n",
      static_cast<unsigned long long>(frames), static_cast<int>(kSampleEvery),
      static_cast<int>(kWarmupFrames), static_cast<double>(rss1) * mib,
      static_cast<double>(rss2) * mib, static_cast<double>(dev1) * mib,
      static_cast<double>(dev2) * mib, swapchains, static_cast<unsigned long long>(counts.volumes),
      static_cast<unsigned long long>(masksBuilt), static_cast<unsigned long long>(counts.masks),
      static_cast<unsigned long long>(counts.fieldReads),
      static_cast<unsigned long long>(counts.stepReads));
  if (rss2 > rss1 + kRssSlack || dev2 > dev1) {
    std::fprintf(stderr,
                 "lic3d-view: error: memory grew during the soak (tolerance: %.0f MiB of "
                 "RSS, no device memory)\n",
                 static_cast<double>(kRssSlack) * mib);
    return cli::kExitFailure;
  }
  return cli::kExitOk;
}

}  // namespace lic3d::viewer
