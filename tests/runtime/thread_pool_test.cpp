// ThreadPool (wirerig/runtime/parallel.h): every task runs once, and a Run's tasks run on the
// pool's threads at the same time, from the very first Run of a fresh pool.
#include "wirerig/runtime/parallel.h"

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace wirerig {
namespace {

// Each of `count` tasks arrives, then waits (up to 20 s) until all have arrived: they can all
// finish only if they all run at once. Returns how many saw every other arrive.
std::size_t TasksThatMet(const ThreadPool& pool, std::size_t count) {
  std::atomic<std::size_t> arrived{0}, met{0};
  RunEach(&pool, count, [&](std::size_t) {
    arrived.fetch_add(1);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (arrived.load() < count && std::chrono::steady_clock::now() < deadline)
      std::this_thread::yield();
    if (arrived.load() == count) met.fetch_add(1);
  });
  return met.load();
}

TEST(ThreadPool, TheFirstRunOfAFreshPoolUsesEveryThread) {
  // The Run is published as soon as the pool exists, before its worker has first run (the
  // worker used to take the generation it first saw as already done, and sat the Run out).
  for (int round = 0; round < 20; ++round) {
    const ThreadPool pool(2);
    ASSERT_EQ(TasksThatMet(pool, 2), 2u) << "round " << round;
  }
  const ThreadPool pool(3);
  EXPECT_EQ(TasksThatMet(pool, 3), 3u);
  EXPECT_EQ(TasksThatMet(pool, 3), 3u);  // and the Runs after it
}

TEST(ThreadPool, RunsEveryTaskOnceAndReturnsAfterAll) {
  const ThreadPool pool(2);
  for (std::size_t count : {0u, 1u, 2u, 7u, 1000u}) {
    std::vector<std::atomic<int>> calls(count);
    pool.Run(
        count,
        [](const void* context, std::size_t k) {
          (*static_cast<std::vector<std::atomic<int>>*>(const_cast<void*>(context)))[k]++;
        },
        &calls);
    for (std::size_t k = 0; k < count; ++k) EXPECT_EQ(calls[k].load(), 1) << count << " " << k;
  }
}

// Back-to-back Runs (a frame's passes) meet workers still spinning after the previous one, or
// asleep after a pause: each task still runs once, and its writes are seen when Run returns.
TEST(ThreadPool, BackToBackRunsWithSpinningAndSleepingWorkers) {
  for (std::size_t threads : {2u, 3u}) {
    const ThreadPool pool(threads);
    std::vector<std::size_t> values(64);
    for (std::size_t round = 0; round < 3000; ++round) {
      const std::size_t count = 2 + round % 63;
      struct Context {
        std::vector<std::size_t>* values;
        std::size_t round;
      } context{&values, round};
      pool.Run(
          count,
          [](const void* c, std::size_t k) {
            const auto* ctx = static_cast<const Context*>(c);
            (*ctx->values)[k] = ctx->round * 100 + k;
          },
          &context);
      for (std::size_t k = 0; k < count; ++k) ASSERT_EQ(values[k], round * 100 + k) << round;
      if (round % 1000 == 999) std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
  }
}

}  // namespace
}  // namespace wirerig
