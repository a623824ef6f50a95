// fault_in (offline/fresh_pages.h): the pages of a range of fresh anonymous memory are resident
// after it and the bytes outside the range are untouched; batch_kinematics into fresh arrays
// (BatchOutput::fresh) writes the same bits as into arrays written before.
#include "mb_kinematics/offline/fresh_pages.h"

#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "mb_kinematics/offline/batch_kinematics.h"
#include "test/support/test_models.h"

namespace {

const std::size_t kPage = static_cast<std::size_t>(sysconf(_SC_PAGESIZE));

// An anonymous private mapping of `pages` pages, unmapped at the end.
struct Mapping {
  explicit Mapping(std::size_t pages) : bytes(pages * kPage) {
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    data = p == MAP_FAILED ? nullptr : static_cast<char*>(p);
  }
  Mapping(const Mapping&) = delete;
  Mapping& operator=(const Mapping&) = delete;
  ~Mapping() {
    if (data) munmap(data, bytes);
  }
  // Whether each page is resident (mincore).
  std::vector<bool> resident() const {
    std::vector<unsigned char> in(bytes / kPage);
    EXPECT_EQ(0, mincore(data, bytes, in.data()));
    return std::vector<bool>(in.begin(), in.end());
  }
  std::size_t bytes;
  char* data = nullptr;
};

TEST(FreshPages, FaultsInExactlyThePagesOfTheRange) {
  Mapping m(8);
  ASSERT_NE(nullptr, m.data);
  // From the middle of page 2 to the middle of page 5: pages 2 to 5.
  mbk::fault_in(m.data + 2 * kPage + 100, 3 * kPage);
  const std::vector<bool> resident = m.resident();
  for (std::size_t p = 0; p < resident.size(); ++p)
    EXPECT_EQ(p >= 2 && p <= 5, resident[p]) << "page " << p;
}

TEST(FreshPages, LeavesBytesOutsideTheRangeAsTheyWere) {
  std::vector<char> memory(5 * kPage, 'x');
  mbk::fault_in(memory.data() + 1000, 2 * kPage);
  for (std::size_t i = 0; i < memory.size(); ++i)
    if (i < 1000 || i >= 1000 + 2 * kPage) ASSERT_EQ('x', memory[i]) << "byte " << i;
  mbk::fault_in(memory.data(), 0);  // nothing to do
}

TEST(FreshPages, BatchIntoFreshArraysWritesTheSameBits) {
  const mbk::Model model = mbk_test::random_tree(17, 9);
  const std::size_t samples = 301;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::vector<double> q(samples * model.nq), v(samples * model.nv), a(samples * model.nv);
  for (std::vector<double>* x : {&q, &v, &a})
    for (double& value : *x) value = u(rng);
  mbk::BatchInput in;
  in.samples = samples;
  in.position = q.data();
  in.velocity = v.data();
  in.acceleration = a.data();
  mbk::BatchOutput<double> touched, fresh;
  for (int k = 1; k <= model.body_count(); ++k) touched.bodies.push_back(k);
  fresh.bodies = touched.bodies;
  std::vector<std::vector<double>> arrays;
  std::vector<std::unique_ptr<Mapping>> mappings;
  arrays.reserve(mbk::kBatchFieldCount);
  for (int f = 0; f < mbk::kBatchFieldCount; ++f) {
    const std::size_t size =
        samples * mbk::batch_field_size(model, static_cast<mbk::BatchField>(f), 17);
    arrays.emplace_back(size, -7.0);
    touched.field[f] = arrays.back().data();
    mappings.push_back(std::make_unique<Mapping>((size * sizeof(double) + kPage - 1) / kPage + 1));
    ASSERT_NE(nullptr, mappings.back()->data);
    // 8 bytes past a page's start: rows and pages do not line up.
    fresh.field[f] = reinterpret_cast<double*>(mappings.back()->data + 8);
    fresh.fresh[f] = true;
  }
  mbk::batch_kinematics(model, in, touched, 1);
  mbk::batch_kinematics(model, in, fresh, 3);
  for (int f = 0; f < mbk::kBatchFieldCount; ++f)
    EXPECT_EQ(0, std::memcmp(touched.field[f], fresh.field[f], arrays[f].size() * sizeof(double)))
        << mbk::batch_field_traits(static_cast<mbk::BatchField>(f)).name;
}

}  // namespace
