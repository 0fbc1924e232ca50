#include "boxpile/sim/thread_pool.hpp"

namespace boxpile {

ThreadPool::ThreadPool(int threads) {
  const int extra = std::max(0, threads - 1);
  workers_.reserve(static_cast<std::size_t>(extra));
  for (int w = 1; w <= extra; ++w) workers_.emplace_back([this, w] { work(w); });
}

ThreadPool::~ThreadPool() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& t : workers_) t.join();
}

void ThreadPool::dispatch(int count, void* task, Trampoline call) {
  std::uint32_t run = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    run = ++run_;
    task_ = task;
    call_ = call;
    count_ = count;
    finished_.store(0, std::memory_order_relaxed);
    // Item 0 is the caller's: the largest item goes first (Islands::by_size), and a worker that
    // took it and then lost its core to another process would keep the caller waiting for it.
    next_.store((static_cast<std::uint64_t>(run) << 32) | 1u, std::memory_order_release);
  }
  wake_.notify_all();
  call(task, 0, 0);
  finished_.fetch_add(1, std::memory_order_acq_rel);
  drain(run, task, call, count, 0);
  // What is left is under way on a worker: a short wait.
  while (finished_.load(std::memory_order_acquire) < count) std::this_thread::yield();
}

void ThreadPool::drain(std::uint32_t run, void* task, Trampoline call, int count, int worker) {
  for (;;) {
    std::uint64_t next = next_.load(std::memory_order_acquire);
    int item = 0;
    do {
      if (static_cast<std::uint32_t>(next >> 32) != run) return;  // a later run has begun
      item = static_cast<int>(next & 0xffffffffu);
      if (item >= count) return;
    } while (!next_.compare_exchange_weak(next, next + 1, std::memory_order_acq_rel, std::memory_order_acquire));
    call(task, item, worker);
    finished_.fetch_add(1, std::memory_order_acq_rel);
  }
}

void ThreadPool::work(int worker) {
  std::uint32_t seen = 0;
  for (;;) {
    std::uint32_t run = 0;
    void* task = nullptr;
    Trampoline call = nullptr;
    int count = 0;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || run_ != seen; });
      if (stop_) return;
      seen = run = run_;
      task = task_;
      call = call_;
      count = count_;
    }
    drain(run, task, call, count, worker);
  }
}

int resolve_threads(int setting) {
  if (setting > 0) return setting;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

}  // namespace boxpile
