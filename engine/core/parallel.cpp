// SPDX-License-Identifier: BSD-3-Clause
#include "core/parallel.h"

#include <sched.h>
#include <sys/mman.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace lic3d {

namespace {

std::atomic<unsigned>& threadLimit() {
  static std::atomic<unsigned> limit{0};
  return limit;
}

}  // namespace

void setThreadLimit(unsigned threads) { threadLimit() = threads; }

unsigned availableThreads() {
  unsigned available = std::max(1u, std::thread::hardware_concurrency());
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) {
    const int count = CPU_COUNT(&set);
    if (count > 0) available = static_cast<unsigned>(count);
  }
  const unsigned limit = threadLimit();
  return limit > 0 ? std::min(available, limit) : available;
}

void parallelChunks(std::size_t count, const std::function<void(std::size_t, std::size_t)>& chunk,
                    std::size_t grain) {
  if (count == 0) return;
  const std::size_t threads = availableThreads();
  // A few chunks per thread evens out uneven ones; none smaller than `grain`.
  const std::size_t size = std::max(grain, (count + 4 * threads - 1) / (4 * threads));
  const std::size_t chunks = (count + size - 1) / size;
  if (chunks == 1) {
    chunk(0, count);
    return;
  }
  parallelFor(chunks, 0, [&](std::size_t c) { chunk(c * size, std::min(count, (c + 1) * size)); });
}

void parallelCopy(void* to, const void* from, std::size_t bytes) {
  parallelChunks(
      bytes,
      [&](std::size_t begin, std::size_t end) {
        std::memcpy(static_cast<std::byte*>(to) + begin,
                    static_cast<const std::byte*>(from) + begin, end - begin);
      },
      std::size_t{1} << 20);
}

void parallelFor(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& task,
                 const ProgressCallback& progress) {
  std::vector<std::exception_ptr> failures(count);
  std::atomic<std::size_t> next{0};
  std::atomic<std::size_t> finished{0};
  const auto work = [&](bool reports) {
    for (std::size_t i = next++; i < count && !progress.stopRequested(); i = next++) {
      try {
        task(i);
      } catch (...) {
        failures[i] = std::current_exception();
      }
      const std::size_t done = ++finished;
      if (reports && progress) progress(static_cast<double>(done) / static_cast<double>(count));
    }
  };
  const std::size_t wanted =
      std::min<std::size_t>(count, threads > 0 ? threads : availableThreads());
  std::vector<std::thread> helpers;
  helpers.reserve(wanted);
  try {
    while (helpers.size() + 1 < wanted) helpers.emplace_back(work, false);
  } catch (const std::system_error&) {
    // No more threads to be had: those started and this one do the rest.
  }
  work(true);
  for (std::thread& helper : helpers) helper.join();
  for (const std::exception_ptr& failure : failures)
    if (failure) std::rethrow_exception(failure);
}

void touchPagesInParallel(void* data, std::size_t bytes) {
  constexpr std::size_t kPage = 4096;
  if (bytes < (std::size_t{64} << 20)) return;
  auto* const first = static_cast<volatile unsigned char*>(data);
  parallelChunks(
      bytes,
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t at = begin; at < end; at += kPage) first[at] = 0;
      },
      std::size_t{8} << 20);
}

void adviseHugePages(void* data, std::size_t bytes) {
  constexpr std::uintptr_t kHuge = std::uintptr_t{2} << 20;
  const auto begin = (reinterpret_cast<std::uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
  const auto end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHuge - 1);
  if (end <= begin) return;
  // Advice only: where the kernel has no transparent huge pages this fails, and nothing changes.
  (void)madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
}

}  // namespace lic3d
