// graph/key_poses: the key poses' sketch (key_pose_sketch).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Eigenvalues>

#include "graph/key_poses.h"

namespace gmg {
namespace {

// keys random poses of 2 d values: positions, then velocities. With `rank` > 0 each part lies in a
// random subspace of that dimension (plus an offset), as a speaker's poses nearly do.
std::vector<double> random_poses(std::size_t keys, std::size_t d, std::size_t rank, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> poses(keys * 2 * d);
  for (std::size_t part = 0; part < 2; ++part) {
    std::vector<double> offset(d), axes(rank * d);
    for (double& v : offset) v = 40.0 * normal(rng);
    for (double& v : axes) v = normal(rng);
    for (std::size_t k = 0; k < keys; ++k) {
      double* p = poses.data() + k * 2 * d + part * d;
      for (std::size_t v = 0; v < d; ++v) p[v] = offset[v];
      if (rank == 0) {
        for (std::size_t v = 0; v < d; ++v) p[v] += 10.0 * normal(rng);
      } else {
        for (std::size_t a = 0; a < rank; ++a) {
          const double c = 10.0 * normal(rng);
          for (std::size_t v = 0; v < d; ++v) p[v] += c * axes[a * d + v];
        }
      }
    }
  }
  return poses;
}

double distance(const double* a, const double* b, std::size_t n) {
  double s = 0.0;
  for (std::size_t i = 0; i < n; ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
  return std::sqrt(s);
}

TEST(KeyPoseSketch, AnOrthonormalBasisOfEachPartAndEveryKeysCoordinates) {
  const std::size_t keys = 300, d = 30;
  const Samples<double> poses(random_poses(keys, d, 0, 1));
  const KeyPoseSketch s = key_pose_sketch(poses, static_cast<int>(2 * d));
  ASSERT_EQ(s.axes, kSketchAxes);
  const std::size_t axes = kSketchAxes, rows = 2 * axes, dims = 2 * d;
  ASSERT_EQ(s.basis.size(), rows * dims);
  ASSERT_EQ(s.values.size(), keys * rows);
  for (std::size_t i = 0; i < rows; ++i) {
    for (std::size_t v = 0; v < dims; ++v)
      if ((v < d) != (i < axes)) {
        EXPECT_EQ(s.basis[i * dims + v], 0.0) << "row " << i << " value " << v;
      }
    for (std::size_t k = 0; k < rows; ++k) {
      double dot = 0.0;
      for (std::size_t v = 0; v < dims; ++v) dot += s.basis[i * dims + v] * s.basis[k * dims + v];
      EXPECT_NEAR(dot, i == k ? 1.0 : 0.0, 1e-12) << i << ", " << k;
    }
  }
  double scale = 0.0;
  for (std::size_t k = 0; k < keys; ++k) {
    const double* p = poses.data() + k * dims;
    const std::vector<double> zero(d, 0.0);
    scale = std::max({scale, distance(p, zero.data(), d), distance(p + d, zero.data(), d)});
    for (std::size_t i = 0; i < rows; ++i) {
      double c = 0.0;
      for (std::size_t v = 0; v < dims; ++v) c += s.basis[i * dims + v] * p[v];
      EXPECT_NEAR(s.values[k * rows + i], c, 1e-9 * scale) << "key " << k << " axis " << i;
    }
  }
  EXPECT_NEAR(s.scale, scale, 1e-12 * scale);
  // The axes hold nearly all the spread that any 8 orthonormal axes could: the sum of the keys'
  // squared deviations along them against the sum of the 8 largest eigenvalues of each part's
  // scatter matrix (Eigen's eigen-decomposition).
  for (std::size_t part = 0; part < 2; ++part) {
    Eigen::MatrixXd x(static_cast<Eigen::Index>(keys), static_cast<Eigen::Index>(d));
    for (std::size_t k = 0; k < keys; ++k)
      for (std::size_t v = 0; v < d; ++v)
        x(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(v)) = poses.data()[k * dims + part * d + v];
    const Eigen::MatrixXd centred = x.rowwise() - x.colwise().mean();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(centred.transpose() * centred);
    const double best = solver.eigenvalues().tail(static_cast<Eigen::Index>(axes)).sum();
    double held = 0.0;
    for (std::size_t a = part * axes; a < (part + 1) * axes; ++a) {
      double mean = 0.0;
      for (std::size_t k = 0; k < keys; ++k) mean += s.values[k * rows + a] / static_cast<double>(keys);
      for (std::size_t k = 0; k < keys; ++k) held += std::pow(s.values[k * rows + a] - mean, 2);
    }
    EXPECT_LE(held, best * (1 + 1e-9));
    EXPECT_GT(held, 0.98 * best) << "part " << part;
  }
}

// Sketched distances are never above the poses' own, part by part; for poses that vary in fewer
// dimensions than the sketch has axes they are the same distances.
TEST(KeyPoseSketch, SketchedDistancesBoundThePosesDistancesFromBelow) {
  const std::size_t keys = 200, d = 24, axes = kSketchAxes, rows = 2 * axes;
  for (std::size_t rank : {0u, 5u}) {
    const Samples<double> poses(random_poses(keys, d, rank, 7 + static_cast<unsigned>(rank)));
    const KeyPoseSketch s = key_pose_sketch(poses, static_cast<int>(2 * d));
    double worst = 1.0;  // the smallest ratio of sketched to true distance
    for (std::size_t a = 0; a < keys; a += 3)
      for (std::size_t b = a + 1; b < keys; b += 5)
        for (std::size_t part = 0; part < 2; ++part) {
          const double truth = distance(poses.data() + a * 2 * d + part * d, poses.data() + b * 2 * d + part * d, d);
          const double sketched =
              distance(s.values.data() + a * rows + part * axes, s.values.data() + b * rows + part * axes, axes);
          EXPECT_LE(sketched, truth * (1 + 1e-12)) << rank << ": keys " << a << ", " << b;
          worst = std::min(worst, sketched / truth);
        }
    if (rank > 0) {
      EXPECT_GT(worst, 1.0 - 1e-9) << "a subspace the axes cover";
    } else {
      EXPECT_LT(worst, 0.9) << "random poses in 24 dimensions: 8 axes miss some of each distance";
    }
  }
}

TEST(KeyPoseSketch, NoKeysNoSketch) {
  EXPECT_EQ(key_pose_sketch(Samples<double>(), 12).axes, 0);
  const KeyPoseSketch small = key_pose_sketch(Samples<double>(random_poses(3, 2, 0, 3)), 4);
  EXPECT_EQ(small.axes, 2);  // no more axes than a part has values
  EXPECT_EQ(small.values.size(), 3u * 4u);
}

}  // namespace
}  // namespace gmg
