// A fixed set of worker threads that run one parallel loop at a time: task(item, worker) for every
// item of [0, count), the caller's thread taking part as worker 0. Made when a world is built and
// kept, so a step starts no thread and allocates nothing: the task is passed as a pointer to the
// caller's callable, not as a std::function. The caller takes items too and never waits for a
// worker that has not woken. Items are handed out one at a time from an atomic counter, so which worker runs which item changes from run to run: a task must write only what
// its item owns, and keep what it counts in its worker's own slot, for the results to be the same
// whatever the number of threads.
#pragma once

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace boxpile {

class ThreadPool {
 public:
  // `threads` >= 1 workers in all, the caller's thread included (1: no thread is started).
  explicit ThreadPool(int threads);
  ~ThreadPool();
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }

  // The least work (seconds on one thread) that the other workers could take over from the caller
  // for a run to be shared: below it, waking a worker and handing it items costs more than it takes
  // over. Measured on the bone scene (AMD EPYC, 2 cores): its islands outside the largest, some 48
  // contacts (about 25 us), ran 15% slower a step on two threads than on one.
  static constexpr double kMinSharedSeconds = 32e-6;
  // Whether a run whose items other than the caller's take `shareable_seconds` is shared.
  bool shares(double shareable_seconds) const { return !workers_.empty() && shareable_seconds >= kMinSharedSeconds; }

  // Runs task(item, worker) for every item in [0, count) and returns when all have run; item 0
  // runs on the caller's thread (give the largest that number). `shareable_seconds` is what the
  // items other than item 0 cost on one thread, as estimated by the caller: when too little to
  // share (shares), as with one worker or one item, the items run in order on the caller's thread.
  // Which worker runs an item never changes its result, so the two ways give the same results.
  template <class Task>
  void run(int count, Task&& task, double shareable_seconds) {
    if (count <= 0) return;
    if (count == 1 || !shares(shareable_seconds)) {
      for (int i = 0; i < count; ++i) task(i, 0);
      return;
    }
    using T = std::remove_reference_t<Task>;
    dispatch(count, const_cast<void*>(static_cast<const void*>(&task)),
             [](void* t, int item, int worker) { (*static_cast<T*>(t))(item, worker); });
  }

 private:
  using Trampoline = void (*)(void*, int, int);
  void dispatch(int count, void* task, Trampoline call);
  void work(int worker);  // a worker thread's loop
  // Takes items of run `run` until none is left (or another run has begun).
  void drain(std::uint32_t run, void* task, Trampoline call, int count, int worker);

  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  // The current run, read by a waking worker under the mutex.
  std::uint32_t run_ = 0;
  void* task_ = nullptr;
  Trampoline call_ = nullptr;
  int count_ = 0;
  // The run's number (high 32 bits) and its next item (low 32 bits), taken in one compare and
  // swap, so that a worker still holding an earlier run takes none of this one's items; and the
  // items finished. The caller waits only for items under way, never for a worker that has not
  // woken yet (on a loaded machine a sleeping worker may wait milliseconds for a core).
  std::atomic<std::uint64_t> next_{0};
  std::atomic<int> finished_{0};
};

// The most threads a step may be given (the `solver.threads` setting's range).
inline constexpr int kMaxThreads = 256;

// The number of workers a step uses for the `solver.threads` setting: 0 means every core of the
// machine.
int resolve_threads(int setting);

}  // namespace boxpile
