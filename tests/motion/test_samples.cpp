// Samples: an owned array, or a view onto memory another object keeps alive, copied on write.
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "engine/motion/samples.h"

namespace gmg {
namespace {

TEST(Samples, AViewReadsInPlaceAndKeepsItsOwnerAlive) {
  auto owner = std::make_shared<std::vector<double>>(std::vector<double>{1, 2, 3, 4});
  const double* where = owner->data();
  Samples<double> s = Samples<double>::view(where, 4, owner);
  std::weak_ptr<std::vector<double>> alive = owner;
  owner.reset();
  ASSERT_FALSE(alive.expired());  // the view holds it
  const Samples<double>& c = s;
  EXPECT_TRUE(c.is_view());
  EXPECT_EQ(c.data(), where);
  EXPECT_EQ(c.size(), 4u);
  EXPECT_EQ(c[2], 3.0);
  EXPECT_EQ(c.back(), 4.0);
  Samples<double> copy = s;  // a copy shares the view
  EXPECT_EQ(static_cast<const Samples<double>&>(copy).data(), where);
  s = Samples<double>();
  copy = Samples<double>();
  EXPECT_TRUE(alive.expired());  // the last view gone, the owner goes
}

TEST(Samples, TheFirstChangeCopiesAndLeavesTheViewedMemoryAlone) {
  auto owner = std::make_shared<std::vector<double>>(std::vector<double>{1, 2, 3});
  Samples<double> s = Samples<double>::view(owner->data(), 3, owner);
  s[1] = 20.0;
  EXPECT_FALSE(s.is_view());
  EXPECT_EQ((*owner)[1], 2.0);
  EXPECT_EQ(s, Samples<double>(std::vector<double>{1, 20, 3}));
  Samples<double> t = Samples<double>::view(owner->data(), 3, owner);
  t.push_back(4.0);
  EXPECT_EQ(t, Samples<double>(std::vector<double>{1, 2, 3, 4}));
  Samples<double> u = Samples<double>::view(owner->data(), 3, owner);
  u.insert(static_cast<const Samples<double>&>(u).end(), t.begin(), t.end());  // from another array
  EXPECT_EQ(u.size(), 7u);
  Samples<double> v = Samples<double>::view(owner->data(), 3, owner);
  v.assign(static_cast<const Samples<double>&>(v).begin() + 1, static_cast<const Samples<double>&>(v).end());
  EXPECT_EQ(v, Samples<double>(std::vector<double>{2, 3}));  // from its own view
  EXPECT_EQ(*owner, (std::vector<double>{1, 2, 3}));
}

TEST(Samples, OwnedBehavesAsAVector) {
  Samples<int> s;
  EXPECT_TRUE(s.empty());
  s.reserve(10);
  for (int i = 0; i < 5; ++i) s.push_back(i);
  s.resize(6, 9);
  EXPECT_EQ(s, Samples<int>(std::vector<int>{0, 1, 2, 3, 4, 9}));
  s.assign(3, 7);
  EXPECT_EQ(s, Samples<int>(std::vector<int>{7, 7, 7}));
  s.clear();
  EXPECT_TRUE(s.empty());
  EXPECT_FALSE(s.is_view());
}

}  // namespace
}  // namespace gmg
