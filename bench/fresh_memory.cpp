// bench/fresh_memory.cpp — what first-touching memory costs on this machine, on one thread and on
// two: a buffer advised for transparent huge pages is written once per 4 KB page, (a) "reused":
// right after the process freed the same amount, (b) "fresh": after a pause in which the kernel may
// hand freed memory back to the hypervisor (virtio-balloon free page reporting). Large outputs
// (the volume assembly's ~1.5 GB, a 64-source distance matrix) pay (b) in a fresh process; the
// ratios tell whether a second thread can help with it (docs/benchmarks.md, "Fresh memory").
//   polydec_fresh_memory [MiB=1024] [rounds=4] [pause seconds=5] [small: 4 KB pages]
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <sys/mman.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace {

constexpr std::size_t kHuge = std::size_t(2) << 20;

// Maps `bytes` (2 MB aligned), writes one byte per 4 KB page on T threads (contiguous shares),
// unmaps; returns the wall time of the writes in ms.
double touch(std::size_t bytes, int T, bool huge) {
  void* raw = mmap(nullptr, bytes + kHuge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (raw == MAP_FAILED) {
    std::perror("mmap");
    std::exit(1);
  }
  char* p = reinterpret_cast<char*>((reinterpret_cast<std::uintptr_t>(raw) + kHuge - 1) & ~(kHuge - 1));
  madvise(p, bytes, huge ? MADV_HUGEPAGE : MADV_NOHUGEPAGE);
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::thread> threads;
  for (int t = 0; t < T; ++t)
    threads.emplace_back([=] {
      for (std::size_t i = bytes * t / T / 4096 * 4096; i < bytes * (t + 1) / T; i += 4096) p[i] = 1;
    });
  for (auto& th : threads) th.join();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  munmap(raw, bytes + kHuge);
  return ms;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

std::string first_line(const char* path) {
  std::ifstream in(path);
  std::string line;
  return std::getline(in, line) ? line : "(not present)";
}

}  // namespace

int main(int argc, char** argv) {
  const long mib = argc > 1 ? std::atol(argv[1]) : 1024;
  const int rounds = argc > 2 ? std::atoi(argv[2]) : 4;
  const int pause = argc > 3 ? std::atoi(argv[3]) : 5;
  const bool huge = !(argc > 4 && std::strcmp(argv[4], "small") == 0);
  if (mib < 4 || rounds < 1 || pause < 0) {
    std::fprintf(stderr, "usage: polydec_fresh_memory [MiB >= 4] [rounds >= 1] [pause seconds >= 0] [small]\n");
    return 2;
  }
  const std::size_t bytes = std::size_t(mib) << 20;
  std::printf("transparent huge pages: %s; defrag: %s\n",
              first_line("/sys/kernel/mm/transparent_hugepage/enabled").c_str(),
              first_line("/sys/kernel/mm/transparent_hugepage/defrag").c_str());
  std::printf("free page reporting: order %s, min_free_ms %s, max_waiting_mib %s\n",
              first_line("/sys/module/page_reporting/parameters/page_reporting_order").c_str(),
              first_line("/sys/module/page_reporting/parameters/min_free_ms").c_str(),
              first_line("/sys/module/page_reporting/parameters/max_waiting_mib").c_str());
  std::vector<double> fresh[2], reused[2];
  for (int r = 0; r < rounds; ++r)
    for (int k = 0; k < 2; ++k) {
      const int T = (k == 0) == (r % 2 == 0) ? 1 : 2;  // order 1,2 then 2,1: neither always goes first
      sleep(unsigned(pause));
      fresh[T - 1].push_back(touch(bytes, T, huge));
      reused[T - 1].push_back(touch(bytes, T, huge));
      std::printf("round %d, %d thread%s: fresh %.1f ms, reused %.1f ms\n", r, T, T > 1 ? "s" : "",
                  fresh[T - 1].back(), reused[T - 1].back());
    }
  const double f1 = median(fresh[0]), f2 = median(fresh[1]), r1 = median(reused[0]), r2 = median(reused[1]);
  std::printf("%ld MiB on %s pages, medians of %d: fresh 1 thread %.1f ms, 2 threads %.1f ms (%.2fx); "
              "reused 1 thread %.1f ms, 2 threads %.1f ms (%.2fx); fresh / reused on 1 thread %.1fx\n",
              mib, huge ? "huge" : "4 KB", rounds, f1, f2, f1 / f2, r1, r2, r1 / r2, f1 / r1);
}
