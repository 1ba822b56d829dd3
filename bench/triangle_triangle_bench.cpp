// Cost per call of the exact triangle-triangle primitives (the inner loop of an
// exact contact query) on jaw-like triangles (edges ~0.5 mm, coordinates
// ~50 mm) in three regimes: far (0.3..2 mm apart), near (within the 0.1 mm band,
// not touching) and intersecting. Each benchmark cycles through a pool of
// pairs so that branches are not trivially predicted; time per iteration is
// time per call.
#include <benchmark/benchmark.h>

#include <array>
#include <cstddef>
#include <random>
#include <vector>

#include "occlude/collision/triangle_triangle.h"

namespace occlude::collision {
namespace {

using Vec = Eigen::Vector3d;

constexpr double kBand = 0.1;  ///< contact band of TrianglesWithin, mm
constexpr std::size_t kPoolSize = 4096;

struct TriPair {
  std::array<Vec, 3> a;
  std::array<Vec, 3> b;
};

enum class Regime { kFar, kNear, kIntersecting };

bool InRegime(double distance, Regime regime) {
  switch (regime) {
    case Regime::kFar:
      return distance >= 0.3 && distance <= 2.0;
    case Regime::kNear:
      return distance > 0.0 && distance <= kBand;
    case Regime::kIntersecting:
      return distance == 0.0;
  }
  return false;
}

/// kPoolSize random pairs of the regime (fixed seed).
const std::vector<TriPair>& Pool(Regime regime) {
  static const auto make = [](Regime r) {
    std::mt19937 rng(1234 + static_cast<unsigned>(r));
    std::uniform_real_distribution<double> u(-1, 1);
    std::uniform_real_distribution<double> reach(0, r == Regime::kFar ? 2.5 : 0.6);
    const Vec center(50, 30, 20);
    std::vector<TriPair> pool;
    while (pool.size() < kPoolSize) {
      TriPair p;
      const Vec shift = Vec(u(rng), u(rng), u(rng)).normalized() * reach(rng);
      for (Vec& v : p.a) v = center + 0.35 * Vec(u(rng), u(rng), u(rng));
      for (Vec& v : p.b) v = center + shift + 0.35 * Vec(u(rng), u(rng), u(rng));
      const double d =
          TriangleTriangleDistance(p.a[0], p.a[1], p.a[2], p.b[0], p.b[1], p.b[2]).distance;
      if (InRegime(d, r)) pool.push_back(p);
    }
    return pool;
  };
  static const std::array<std::vector<TriPair>, 3> pools = {make(Regime::kFar), make(Regime::kNear),
                                                            make(Regime::kIntersecting)};
  return pools[static_cast<std::size_t>(regime)];
}

void BM_TrianglesIntersect(benchmark::State& state) {
  const auto& pool = Pool(static_cast<Regime>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const TriPair& p = pool[i++ % pool.size()];
    benchmark::DoNotOptimize(TrianglesIntersect(p.a[0], p.a[1], p.a[2], p.b[0], p.b[1], p.b[2]));
  }
}

void BM_TriangleTriangleDistance(benchmark::State& state) {
  const auto& pool = Pool(static_cast<Regime>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const TriPair& p = pool[i++ % pool.size()];
    benchmark::DoNotOptimize(
        TriangleTriangleDistance(p.a[0], p.a[1], p.a[2], p.b[0], p.b[1], p.b[2]));
  }
}

void BM_TrianglesWithinBand(benchmark::State& state) {
  const auto& pool = Pool(static_cast<Regime>(state.range(0)));
  std::size_t i = 0;
  TriangleDistance out;
  for (auto _ : state) {
    const TriPair& p = pool[i++ % pool.size()];
    benchmark::DoNotOptimize(
        TrianglesWithin(p.a[0], p.a[1], p.a[2], p.b[0], p.b[1], p.b[2], kBand, &out));
    benchmark::ClobberMemory();
  }
}

// Argument: 0 = far, 1 = near (within 0.1 mm), 2 = intersecting.
BENCHMARK(BM_TrianglesIntersect)->ArgName("far0_near1_hit2")->DenseRange(0, 2);
BENCHMARK(BM_TriangleTriangleDistance)->ArgName("far0_near1_hit2")->DenseRange(0, 2);
BENCHMARK(BM_TrianglesWithinBand)->ArgName("far0_near1_hit2")->DenseRange(0, 2);

}  // namespace
}  // namespace occlude::collision
