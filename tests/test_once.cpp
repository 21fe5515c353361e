// The executables' pthread_once (cli/pthread_once.cpp), as std::call_once and
// CGAL's lazy numbers use it: each callable runs once, every caller returns
// after it has finished, a callable that throws lets a later call run it again.
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

extern "C" const int vismap_pthread_once_replaced;

namespace {

constexpr int kThreads = 8;

// Runs f(t) on kThreads threads that start together.
template <class F>
void together(F&& f) {
  std::atomic<int> ready{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      ready.fetch_add(1);
      while (ready.load() < kThreads) std::this_thread::yield();
      f(t);
    });
  for (std::thread& th : threads) th.join();
}

TEST(PthreadOnce, TheReplacementIsLinked) { EXPECT_EQ(vismap_pthread_once_replaced, 1); }

TEST(PthreadOnce, RunsOnceAndEveryCallerSeesItDone) {
  for (int round = 0; round < 200; ++round) {
    std::once_flag flag;
    std::atomic<int> runs{0};
    int value = 0;   // (written inside the callable, read after call_once returns)
    std::atomic<int> wrong{0};
    together([&](int) {
      std::call_once(flag, [&] {
        if (round % 20 == 0) std::this_thread::sleep_for(std::chrono::milliseconds(5));   // (others wait)
        value = 42;
        runs.fetch_add(1);
      });
      if (value != 42) wrong.fetch_add(1);
    });
    ASSERT_EQ(runs.load(), 1) << "round " << round;
    ASSERT_EQ(wrong.load(), 0) << "round " << round;
  }
}

TEST(PthreadOnce, AThrowingCallableRunsAgainOnTheNextCall) {
  std::once_flag flag;
  int runs = 0;
  EXPECT_THROW(std::call_once(flag, [&] { ++runs; throw std::runtime_error("first"); }), std::runtime_error);
  std::call_once(flag, [&] { ++runs; });
  std::call_once(flag, [&] { ++runs; });
  EXPECT_EQ(runs, 2);
}

TEST(PthreadOnce, WaitersWakeWhenTheRunningCallThrows) {
  std::once_flag flag;
  std::atomic<int> runs{0}, threw{0};
  together([&](int) {
    try {
      std::call_once(flag, [&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        if (runs.fetch_add(1) == 0) throw std::runtime_error("first");
      });
    } catch (const std::runtime_error&) {
      threw.fetch_add(1);
    }
  });
  EXPECT_EQ(threw.load(), 1);
  EXPECT_EQ(runs.load(), 2);   // the one that threw, then one that finished
}

// CGAL's lazy numbers shared by threads: each exact value made once, the same for all.
TEST(PthreadOnce, LazyNumbersSharedByThreads) {
  using FT = CGAL::Epeck::FT;
  std::vector<FT> numbers;
  for (int i = 1; i <= 2000; ++i) numbers.push_back(FT(1) / FT(i) + FT(i) / FT(3));
  std::vector<std::vector<CGAL::Epeck::FT::ET>> seen(kThreads);
  together([&](int t) {
    for (std::size_t k = 0; k < numbers.size(); ++k) {
      const std::size_t i = (k * 7 + static_cast<std::size_t>(t) * 131) % numbers.size();   // (each thread its own order)
      seen[static_cast<std::size_t>(t)].push_back(numbers[i].exact());
    }
  });
  for (int t = 0; t < kThreads; ++t)
    for (std::size_t k = 0; k < numbers.size(); ++k) {
      const std::size_t i = (k * 7 + static_cast<std::size_t>(t) * 131) % numbers.size();
      ASSERT_EQ(seen[static_cast<std::size_t>(t)][k], FT::ET(1) / FT::ET(static_cast<int>(i + 1)) +
                                                           FT::ET(static_cast<int>(i + 1)) / FT::ET(3));
    }
}

}  // namespace
