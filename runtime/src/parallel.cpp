// ThreadPool: workers sleep on a condition variable until a Run publishes a new generation of
// tasks; every participant (the workers and the calling thread) claims task indices from one
// atomic counter. A Run returns once every task has finished; the next Run first waits until
// every worker that joined the previous generation has left it, so no worker can claim an
// index of a new generation with the old generation's task.
//
// A frame runs several Runs back to back (the vertex stage's passes), a few microseconds
// apart. Waking a sleeping thread costs tens of microseconds, each way, per Run; so a worker
// that finishes a generation, and a Run waiting for its tasks, first spin (reading atomics, no
// lock) for up to kSpin before they sleep. The spinning only delays the same waits: every change
// of state still happens under the mutex, as without it.
#include "wirerig/runtime/parallel.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <thread>
#include <vector>

#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__)
#include <immintrin.h>
#endif

namespace wirerig {
namespace {

constexpr std::chrono::microseconds kSpin{100};

inline void CpuRelax() {
#if defined(__x86_64__) || defined(_M_X64) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

// Spins until `done()` or kSpin has passed; returns done().
template <class Done>
bool SpinUntil(Done done) {
  const auto start = std::chrono::steady_clock::now();
  for (unsigned i = 1;; ++i) {
    if (done()) return true;
    CpuRelax();
    if (i % 64 == 0 && std::chrono::steady_clock::now() - start > kSpin) return done();
  }
}

}  // namespace

struct ThreadPool::State {
  std::mutex run_mutex;  // one Run at a time
  std::mutex mutex;
  std::condition_variable wake;  // workers: a new generation or stop
  std::condition_variable idle;  // Run: tasks finished, workers left
  // Written under `mutex`; atomic so that spinners may read them without it.
  std::atomic<std::uint64_t> generation{0};
  std::atomic<bool> stop{false};
  std::atomic<std::size_t> completed{0};  // tasks finished in this generation
  Task task = nullptr;
  const void* context = nullptr;
  std::size_t count = 0;
  std::size_t busy = 0;  // workers inside this generation
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
    // Generation 0 is the pool's creation: a worker that first runs after a Run has already
    // published generation 1 still joins it.
    std::uint64_t seen = 0;
    for (;;) {
      SpinUntil([&] { return stop.load() || generation.load() != seen; });
      std::unique_lock<std::mutex> lock(mutex);
      wake.wait(lock, [&] { return stop.load() || generation.load() != seen; });
      if (stop.load()) return;
      seen = generation.load();
      const Task t = task;
      const void* c = context;
      const std::size_t n = count;
      ++busy;
      lock.unlock();
      const std::size_t done = Work(t, c, n);
      lock.lock();
      completed.fetch_add(done);
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
    state_->stop.store(true);
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
    s.completed.store(0);
    s.next.store(0, std::memory_order_relaxed);
    s.generation.fetch_add(1);
  }
  s.wake.notify_all();
  const std::size_t done = s.Work(task, context, count);
  s.completed.fetch_add(done);
  SpinUntil([&] { return s.completed.load() == count; });
  std::unique_lock<std::mutex> lock(s.mutex);
  s.idle.wait(lock, [&] { return s.completed.load() == count; });
}

}  // namespace wirerig
