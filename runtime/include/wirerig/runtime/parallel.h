// Parallel loops for the jobs that offer them (EvaluateRigJob's vertex and normal passes,
// profile generation in wirerig::rig). A job given a ParallelFor splits a pass into independent
// tasks whose outputs never overlap, so its results are bit-identical whatever the number of
// threads. Without one (the default) everything runs on the calling thread.
#pragma once

#include <cstddef>
#include <memory>

namespace wirerig {

class ParallelFor {
 public:
  using Task = void (*)(const void* context, std::size_t index);
  virtual ~ParallelFor() = default;
  // Calls task(context, k) exactly once for every k in [0, count), possibly concurrently and
  // from other threads, and returns when every call has returned. Tasks do not throw.
  virtual void Run(std::size_t count, Task task, const void* context) const = 0;
  // How many threads may run tasks at once (at least 1).
  virtual std::size_t concurrency() const = 0;
};

// Runs `count` tasks through `parallel`, or on the calling thread when it is null.
inline void RunTasks(const ParallelFor* parallel, std::size_t count, ParallelFor::Task task,
                     const void* context) {
  if (parallel == nullptr || count <= 1) {
    for (std::size_t k = 0; k < count; ++k) task(context, k);
  } else {
    parallel->Run(count, task, context);
  }
}

// RunTasks with a callable: f(k) for every k in [0, count).
template <class F>
void RunEach(const ParallelFor* parallel, std::size_t count, const F& f) {
  RunTasks(
      parallel, count,
      [](const void* context, std::size_t k) { (*static_cast<const F*>(context))(k); }, &f);
}

// A fixed set of threads - 1 workers that, with the calling thread, run each Run's tasks.
// Create it once (creation allocates and starts the threads); Run itself never allocates.
// Calls to Run from several threads are serialised; a task must not call Run on the same pool.
// The destructor stops and joins the workers.
class ThreadPool final : public ParallelFor {
 public:
  explicit ThreadPool(std::size_t threads);  // threads < 1 counts as 1 (no workers)
  ~ThreadPool() override;
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  void Run(std::size_t count, Task task, const void* context) const override;
  std::size_t concurrency() const override;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace wirerig
