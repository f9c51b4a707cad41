// ThreadPool: workers sleep on a condition variable until a Run publishes a new generation of
// tasks; every participant (the workers and the calling thread) claims task indices from one
// atomic counter. A Run returns once every task has finished; the next Run first waits until
// every worker that joined the previous generation has left it, so no worker can claim an
// index of a new generation with the old generation's task.
#include "wirerig/runtime/parallel.h"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

namespace wirerig {

struct ThreadPool::State {
  std::mutex run_mutex;  // one Run at a time
  std::mutex mutex;
  std::condition_variable wake;  // workers: a new generation or stop
  std::condition_variable idle;  // Run: tasks finished, workers left
  std::uint64_t generation = 0;
  bool stop = false;
  Task task = nullptr;
  const void* context = nullptr;
  std::size_t count = 0;
  std::size_t completed = 0;  // tasks finished in this generation
  std::size_t busy = 0;       // workers inside this generation
  std::atomic<std::size_t> next{0};
  std::vector<std::thread> workers;

  // Claims and runs tasks until none is left; returns how many it ran.
  std::size_t Work(Task t, const void* c, std::size_t n) {
    std::size_t done = 0;
    for (std::size_t k = next.fetch_add(1, std::memory_order_relaxed); k < n;
         k = next.fetch_add(1, std::memory_order_relaxed)) {
      t(c, k);
      ++done;
    }
    return done;
  }

  void Loop() {
    std::unique_lock<std::mutex> lock(mutex);
    std::uint64_t seen = generation;
    for (;;) {
      wake.wait(lock, [&] { return stop || generation != seen; });
      if (stop) return;
      seen = generation;
      const Task t = task;
      const void* c = context;
      const std::size_t n = count;
      ++busy;
      lock.unlock();
      const std::size_t done = Work(t, c, n);
      lock.lock();
      completed += done;
      --busy;
      idle.notify_all();
    }
  }
};

ThreadPool::ThreadPool(std::size_t threads) : state_(std::make_unique<State>()) {
  for (std::size_t k = 1; k < threads; ++k)
    state_->workers.emplace_back([s = state_.get()] { s->Loop(); });
}

ThreadPool::~ThreadPool() {
  {
    const std::lock_guard<std::mutex> lock(state_->mutex);
    state_->stop = true;
  }
  state_->wake.notify_all();
  for (std::thread& worker : state_->workers) worker.join();
}

std::size_t ThreadPool::concurrency() const { return state_->workers.size() + 1; }

void ThreadPool::Run(std::size_t count, Task task, const void* context) const {
  State& s = *state_;
  if (s.workers.empty() || count <= 1) {
    for (std::size_t k = 0; k < count; ++k) task(context, k);
    return;
  }
  const std::lock_guard<std::mutex> serial(s.run_mutex);
  {
    std::unique_lock<std::mutex> lock(s.mutex);
    s.idle.wait(lock, [&] { return s.busy == 0; });
    s.task = task;
    s.context = context;
    s.count = count;
    s.completed = 0;
    s.next.store(0, std::memory_order_relaxed);
    ++s.generation;
  }
  s.wake.notify_all();
  const std::size_t done = s.Work(task, context, count);
  std::unique_lock<std::mutex> lock(s.mutex);
  s.completed += done;
  s.idle.wait(lock, [&] { return s.completed == count; });
}

}  // namespace wirerig
