// dec/detail/threads.h — how the library runs work on threads: a requested thread count resolved
// (0: all hardware threads), and a job run on threads 0..T-1 (0 on the calling thread), all
// joined before returning. Every threaded routine gives results independent of T.
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace polydec {

// `requested` threads, or the hardware's count for 0; at least 1.
inline int resolve_threads(int requested) {
  return std::max(1, requested > 0 ? requested : int(std::thread::hardware_concurrency()));
}

// Calls job(t) for t = 0..T-1, job(0) on the calling thread, and waits for all.
template <class Job>
void run_on_threads(int T, Job&& job) {
  std::vector<std::jthread> workers;
  for (int t = 1; t < T; ++t) workers.emplace_back(job, t);
  job(0);
}

}  // namespace polydec
