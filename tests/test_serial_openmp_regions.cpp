// SerialOpenMpRegions: OpenMP regions run inline inside the scope, untouched outside it.
#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <thread>

#include "engine/solver/serial_openmp_regions.hpp"

namespace rockdd {
namespace {

int team_size_of_a_region() {
  int size = 0;
#pragma omp parallel num_threads(2)
  {
#pragma omp master
    size = omp_get_num_threads();
  }
  return size;
}

TEST(SerialOpenMpRegions, InsideTheScopeARegionRunsOnceOnTheCallingThread) {
  SerialOpenMpRegions serial;
  std::atomic<int> bodies{0};
  const auto caller = std::this_thread::get_id();
  bool same_thread = true;
#pragma omp parallel num_threads(4)
  {
    ++bodies;
    same_thread = same_thread && std::this_thread::get_id() == caller;
    EXPECT_EQ(omp_get_num_threads(), 1);
    EXPECT_EQ(omp_get_thread_num(), 0);
  }
  EXPECT_EQ(bodies.load(), 1);
  EXPECT_TRUE(same_thread);
}

TEST(SerialOpenMpRegions, ParallelLoopsStillCoverTheWholeRange) {
  SerialOpenMpRegions serial;
  std::vector<int> hit(1000, 0);
#pragma omp parallel for num_threads(4) schedule(static)
  for (int i = 0; i < 1000; ++i) hit[i] += 1;
#pragma omp parallel for num_threads(4) schedule(dynamic, 7)
  for (int i = 0; i < 1000; ++i) hit[i] += 1;
  for (const int h : hit) EXPECT_EQ(h, 2);
}

TEST(SerialOpenMpRegions, OutsideTheScopeOpenMpIsUntouched) {
  if (omp_get_num_procs() < 2) GTEST_SKIP() << "needs two processors";
  EXPECT_EQ(team_size_of_a_region(), 2);
  {
    SerialOpenMpRegions outer;
    {
      SerialOpenMpRegions inner;
      EXPECT_EQ(team_size_of_a_region(), 1);
    }
    EXPECT_TRUE(SerialOpenMpRegions::active());  // the inner scope restored the outer state
  }
  EXPECT_FALSE(SerialOpenMpRegions::active());
  EXPECT_EQ(team_size_of_a_region(), 2);
  // Another thread is not affected by this thread's scope.
  SerialOpenMpRegions serial;
  int other = 0;
  std::thread([&] { other = team_size_of_a_region(); }).join();
  EXPECT_EQ(other, 2);
}

}  // namespace
}  // namespace rockdd
