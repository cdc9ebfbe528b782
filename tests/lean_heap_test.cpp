// The command line's lean heap (app/lean_heap.cpp) hands free memory back to the kernel, some of it by hand (the
// pages of malloc's top chunk, found from glibc's own figures): it must never take a page that holds a live
// block. ctest runs this under the launcher's malloc tunables (tests/CMakeLists.txt), where that path is taken.
#include <gtest/gtest.h>
#include <sys/prctl.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "lean_heap.h"

namespace rayview {
namespace {

struct Block {
  unsigned char* data;
  std::size_t size;
  unsigned char fill;
};

bool intact(const Block& b) {
  for (std::size_t i = 0; i < b.size; ++i)
    if (b.data[i] != static_cast<unsigned char>(b.fill + i)) return false;
  return true;
}

TEST(LeanHeap, HandingMemoryBackKeepsEveryLiveBlock) {
  std::mt19937 random(477);
  std::vector<Block> blocks;
  // Small and large blocks, every other one freed, and a big one freed last so that the heap's top is free and large.
  for (int round = 0; round < 3; ++round) {
    for (int i = 0; i < 3000; ++i) {
      const std::size_t size = 16 + random() % (i % 50 == 0 ? 200000 : 3000);
      auto* data = static_cast<unsigned char*>(std::malloc(size));
      ASSERT_NE(data, nullptr);
      const auto fill = static_cast<unsigned char>(random());
      for (std::size_t k = 0; k < size; ++k) data[k] = static_cast<unsigned char>(fill + k);
      blocks.push_back({data, size, fill});
    }
    for (std::size_t i = blocks.size() - 3000; i < blocks.size(); i += 2) {
      std::free(blocks[i].data);
      blocks[i].data = nullptr;
    }
    void* big = std::malloc(3 << 20);
    std::memset(big, 1, 3 << 20);
    std::free(big);
    if (round == 0) {
      useLeanHeapForEstimate(150'000);
      EXPECT_EQ(::prctl(PR_GET_THP_DISABLE, 0, 0, 0, 0), 1) << "a lean scene's heap is off huge pages";
    } else if (round == 1) {
      useLeanHeap();
    } else {
      useLeanHeapForTheWrite();
      EXPECT_EQ(::prctl(PR_GET_THP_DISABLE, 0, 0, 0, 0), 0) << "and on them again for the write";
    }
    for (const Block& b : blocks) {
      if (b.data) {
        ASSERT_TRUE(intact(b)) << "a live block of " << b.size << " bytes changed";
      }
    }
  }
  // The heap still works: what was handed back is given out again.
  for (int i = 0; i < 2000; ++i) {
    const std::size_t size = 16 + random() % 5000;
    auto* data = static_cast<unsigned char*>(std::malloc(size));
    ASSERT_NE(data, nullptr);
    const auto fill = static_cast<unsigned char>(random());
    for (std::size_t k = 0; k < size; ++k) data[k] = static_cast<unsigned char>(fill + k);
    blocks.push_back({data, size, fill});
  }
  for (const Block& b : blocks)
    if (b.data) {
      ASSERT_TRUE(intact(b)) << "a live block of " << b.size << " bytes changed";
      std::free(b.data);
    }
}

// An estimate under the lean sizes leaves the heap alone (the seven bench scenes keep their huge pages).
TEST(LeanHeap, SmallScenesKeepTheirHeap) {
  void* p = std::malloc(100);
  static_cast<unsigned char*>(p)[0] = 7;
  useLeanHeapForEstimate(95'786);  // killeroo_2020's estimate
  EXPECT_EQ(::prctl(PR_GET_THP_DISABLE, 0, 0, 0, 0), 0);
  EXPECT_EQ(static_cast<unsigned char*>(p)[0], 7);
  std::free(p);
}

}  // namespace
}  // namespace rayview
