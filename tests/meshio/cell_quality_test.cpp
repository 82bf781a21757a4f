// checkPolyMeshCells on meshes large enough for several sweeps (over 131,072 cells), against an
// independent computation written the way OpenFOAM writes it (primitiveMeshFaceCentresAndAreas.C,
// primitiveMeshCellCentresAndVols.C, primitiveMeshCheck.C): every face's centre and area vector
// stored, the cell sums by loops over owner and then neighbour, the checks face by face. The sums
// of a cell add its faces in another order than the check does (owned faces first), so volumes
// and angles agree to rounding, the counts and ids exactly.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "ffdkit/meshio/cell_quality.h"
#include "polymesh_cube.h"

namespace ffdkit::meshio {
namespace {

using Cube = test::PolyMeshCube;

// A unit cube of n^3 hexahedra as blockMesh orders it.
Cube cube(int n) { return test::polyMeshCube(n); }

// Every point moved by up to `amount` in each coordinate.
Eigen::MatrixX3d jittered(const Eigen::MatrixX3d& points, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  Eigen::MatrixX3d moved = points;
  for (Eigen::Index r = 0; r < moved.rows(); ++r)
    for (int c = 0; c < 3; ++c) moved(r, c) += u(rng);
  return moved;
}

// The same cells with every k-th face given other polygons (the order of the faces kept): a
// quadrilateral split in two triangles (f % k == 0), or given a fifth point, the middle of its
// first edge (f % k == 1). The cells' shapes do not change; their faces are no longer all
// quadrilaterals, which the check computes another way.
Cube withOtherPolygons(const Cube& c, int k) {
  Cube r;
  std::int64_t pentagons = 0;
  for (std::int64_t f = 1; f < c.cells.faceCount(); f += k) ++pentagons;
  r.points.resize(c.points.rows() + pentagons, 3);
  r.points.topRows(c.points.rows()) = c.points;
  Eigen::Index middle = c.points.rows();
  r.cells.cellCount = c.cells.cellCount;
  r.cells.faceStarts = {0};
  const std::int64_t internal = std::int64_t(c.cells.neighbour.size());
  for (std::int64_t f = 0; f < c.cells.faceCount(); ++f) {
    auto put = [&](std::initializer_list<std::int32_t> vertices) {
      r.cells.faceVertices.held().insert(r.cells.faceVertices.held().end(), vertices);
      r.cells.faceStarts.push_back(std::int32_t(r.cells.faceVertices.size()));
      r.cells.owner.push_back(c.cells.owner[std::size_t(f)]);
      if (f < internal) r.cells.neighbour.push_back(c.cells.neighbour[std::size_t(f)]);
    };
    const LabelList::const_iterator v = c.cells.faceVertices.begin() + c.cells.faceStarts[std::size_t(f)];
    if (f % k == 0) {
      put({v[0], v[1], v[2]});
      put({v[0], v[2], v[3]});
    } else if (f % k == 1) {
      r.points.row(middle) = 0.5 * (c.points.row(v[0]) + c.points.row(v[1]));
      put({v[0], std::int32_t(middle++), v[1], v[2], v[3]});
    } else {
      put({v[0], v[1], v[2], v[3]});
    }
  }
  return r;
}

// OpenFOAM's check, written out plainly; `badCells`, when given, receives every bad cell in order.
CellQuality reference(const Eigen::MatrixX3d& points, const PolyMeshCells& cells,
                      std::vector<std::int64_t>* badCells = nullptr) {
  const std::int64_t nFaces = cells.faceCount(), nInternal = std::int64_t(cells.neighbour.size()), nCells = cells.cellCount;
  const std::size_t faceTotal = static_cast<std::size_t>(nFaces), cellTotal = static_cast<std::size_t>(nCells);
  std::vector<Eigen::Vector3d> fCtrs(faceTotal), fAreas(faceTotal);
  for (std::int64_t f = 0; f < nFaces; ++f) {
    const std::int32_t begin = cells.faceStarts[std::size_t(f)], n = cells.faceStarts[std::size_t(f) + 1] - begin;
    auto p = [&](std::int32_t i) -> Eigen::Vector3d { return points.row(cells.faceVertices[std::size_t(begin + i % n)]).transpose(); };
    Eigen::Vector3d fCentre = Eigen::Vector3d::Zero();
    for (std::int32_t i = 0; i < n; ++i) fCentre += p(i);
    fCentre /= n;
    Eigen::Vector3d sumN = Eigen::Vector3d::Zero(), sumAc = Eigen::Vector3d::Zero();
    double sumA = 0.0;
    for (std::int32_t i = 0; i < n; ++i) {
      const Eigen::Vector3d c = p(i) + p(i + 1) + fCentre, normal = (p(i + 1) - p(i)).cross(fCentre - p(i));
      sumN += normal;
      sumA += normal.norm();
      sumAc += normal.norm() * c;
    }
    fCtrs[std::size_t(f)] = sumA < 1e-150 ? fCentre : Eigen::Vector3d(sumAc / (3.0 * sumA));
    fAreas[std::size_t(f)] = sumA < 1e-150 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(0.5 * sumN);
  }
  std::vector<Eigen::Vector3d> cEst(cellTotal, Eigen::Vector3d::Zero()), cellCtrs(cellTotal, Eigen::Vector3d::Zero());
  std::vector<double> cellVols(cellTotal, 0.0);
  std::vector<int> nCellFaces(cellTotal, 0);
  for (std::int64_t f = 0; f < nFaces; ++f) {
    cEst[std::size_t(cells.owner[std::size_t(f)])] += fCtrs[std::size_t(f)];
    ++nCellFaces[std::size_t(cells.owner[std::size_t(f)])];
  }
  for (std::int64_t f = 0; f < nInternal; ++f) {
    cEst[std::size_t(cells.neighbour[std::size_t(f)])] += fCtrs[std::size_t(f)];
    ++nCellFaces[std::size_t(cells.neighbour[std::size_t(f)])];
  }
  for (std::int64_t c = 0; c < nCells; ++c) cEst[std::size_t(c)] /= nCellFaces[std::size_t(c)];
  auto addPyramid = [&](std::int64_t f, std::int32_t c, double sign) {
    const double pyr3Vol = sign * fAreas[std::size_t(f)].dot(fCtrs[std::size_t(f)] - cEst[std::size_t(c)]);
    cellCtrs[std::size_t(c)] += pyr3Vol * (0.75 * fCtrs[std::size_t(f)] + 0.25 * cEst[std::size_t(c)]);
    cellVols[std::size_t(c)] += pyr3Vol;
  };
  for (std::int64_t f = 0; f < nFaces; ++f) addPyramid(f, cells.owner[std::size_t(f)], 1.0);
  for (std::int64_t f = 0; f < nInternal; ++f) addPyramid(f, cells.neighbour[std::size_t(f)], -1.0);
  CellQuality q;
  q.cellCount = nCells;
  q.faceCount = nFaces;
  q.minVolume = q.minPyramidVolume = std::numeric_limits<double>::infinity();
  q.maxVolume = -q.minVolume;
  std::vector<bool> bad(cellTotal, false);
  for (std::int64_t c = 0; c < nCells; ++c) {
    double& v = cellVols[std::size_t(c)];
    cellCtrs[std::size_t(c)] = std::abs(v) > 1e-300 ? Eigen::Vector3d(cellCtrs[std::size_t(c)] / v) : cEst[std::size_t(c)];
    v /= 3.0;
    q.minVolume = std::min(q.minVolume, v);
    q.maxVolume = std::max(q.maxVolume, v);
    q.totalVolume += v;
    if (v < 1e-300) {
      ++q.negativeVolumeCells;
      bad[std::size_t(c)] = true;
    }
  }
  double minCosine = 1.0, sumCosines = 0.0;
  for (std::int64_t f = 0; f < nFaces; ++f) {
    const Eigen::Vector3d& fc = fCtrs[std::size_t(f)];
    const Eigen::Vector3d& fa = fAreas[std::size_t(f)];
    const std::int32_t own = cells.owner[std::size_t(f)];
    const Eigen::Vector3d& oc = cellCtrs[std::size_t(own)];
    auto pyramid = [&](double volume, std::int32_t c) {
      q.minPyramidVolume = std::min(q.minPyramidVolume, volume);
      if (volume < -1e-15) {
        ++q.incorrectlyOrientedFaces;
        bad[std::size_t(c)] = true;
      }
    };
    pyramid(fa.dot(fc - oc) / 3.0, own);
    const Eigen::Vector3d cpf = fc - oc;
    Eigen::Vector3d d;
    double spread = 0.2;
    if (f < nInternal) {
      const std::int32_t nei = cells.neighbour[std::size_t(f)];
      const Eigen::Vector3d& nc = cellCtrs[std::size_t(nei)];
      pyramid(fa.dot(nc - fc) / 3.0, nei);
      d = nc - oc;
      const double cosine = d.dot(fa) / (d.norm() * fa.norm() + 1e-150);
      minCosine = std::min(minCosine, cosine);
      sumCosines += cosine;
    } else {
      const Eigen::Vector3d normal = fa / (fa.norm() + 1e-150);
      d = normal * normal.dot(cpf);
      spread = 0.4;
    }
    // primitiveMeshTools.C, faceSkewness / boundaryFaceSkewness.
    const Eigen::Vector3d sv = cpf - (fa.dot(cpf) / (fa.dot(d) + 1e-150)) * d;
    const Eigen::Vector3d svHat = sv / (sv.norm() + 1e-150);
    double fd = spread * d.norm() + 1e-150;
    for (std::int32_t k = cells.faceStarts[std::size_t(f)]; k < cells.faceStarts[std::size_t(f) + 1]; ++k)
      fd = std::max(fd, std::abs(svHat.dot(points.row(cells.faceVertices[std::size_t(k)]).transpose() - fc)));
    q.maxSkewness = std::max(q.maxSkewness, sv.norm() / fd);
  }
  q.maxNonOrthogonality = std::acos(std::clamp(minCosine, -1.0, 1.0)) * 180.0 / std::numbers::pi;
  q.meanNonOrthogonality = std::acos(std::clamp(sumCosines / double(nInternal), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  for (std::int64_t c = 0; c < nCells; ++c)
    if (bad[std::size_t(c)]) {
      ++q.badCells;
      if (q.firstBadCells.size() < 10) q.firstBadCells.push_back(c);
      if (badCells != nullptr) badCells->push_back(c);
    }
  return q;
}

// Volumes and angles to rounding (a cell's faces summed in another order), counts exactly.
void expectAgrees(const CellQuality& expected, const CellQuality& got) {
  const double volumeScale = std::max(std::abs(expected.maxVolume), std::abs(expected.minVolume));
  EXPECT_NEAR(got.minVolume, expected.minVolume, 1e-12 * volumeScale);
  EXPECT_NEAR(got.maxVolume, expected.maxVolume, 1e-12 * volumeScale);
  EXPECT_NEAR(got.totalVolume, expected.totalVolume, 1e-12 * std::abs(expected.totalVolume) + 1e-9 * volumeScale);
  EXPECT_NEAR(got.minPyramidVolume, expected.minPyramidVolume, 1e-10 * volumeScale);
  EXPECT_NEAR(got.maxNonOrthogonality, expected.maxNonOrthogonality, 1e-7);
  EXPECT_NEAR(got.meanNonOrthogonality, expected.meanNonOrthogonality, 1e-7);
  EXPECT_NEAR(got.maxSkewness, expected.maxSkewness, 1e-7 * std::max(1.0, expected.maxSkewness));
  EXPECT_EQ(got.negativeVolumeCells, expected.negativeVolumeCells);
  EXPECT_EQ(got.incorrectlyOrientedFaces, expected.incorrectlyOrientedFaces);
  EXPECT_EQ(got.badCells, expected.badCells);
  EXPECT_EQ(got.firstBadCells, expected.firstBadCells);
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// 54^3 = 157,464 cells: three sweeps, so that faces between sweeps are checked too.
constexpr int kCells = 54;

// The check of `cells` on one thread, after expecting the same bits of every number and the same
// counts and first bad cells on two threads.
CellQuality checkedOnOneAndTwoThreads(const Eigen::MatrixX3d& points, const PolyMeshCells& cells) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const CellQuality one = checkPolyMeshCells(points, cells);
  omp_set_num_threads(std::max(2, threads));
  const CellQuality two = checkPolyMeshCells(points, cells);
  omp_set_num_threads(threads);
  for (auto [a, b] : {std::pair{one.minVolume, two.minVolume}, {one.maxVolume, two.maxVolume}, {one.totalVolume, two.totalVolume},
                      {one.minPyramidVolume, two.minPyramidVolume}, {one.maxNonOrthogonality, two.maxNonOrthogonality},
                      {one.meanNonOrthogonality, two.meanNonOrthogonality}, {one.maxSkewness, two.maxSkewness}})
    EXPECT_TRUE(sameBits(a, b)) << a << " " << b;
  EXPECT_EQ(one.badCells, two.badCells);
  EXPECT_EQ(one.incorrectlyOrientedFaces, two.incorrectlyOrientedFaces);
  EXPECT_EQ(one.firstBadCells, two.firstBadCells);
  return one;
}

TEST(CellQualitySweeps, JitteredAndFoldedCubesAgreeWithOpenFoamsOwnComputation) {
  const Cube c = cube(kCells);
  const Eigen::MatrixX3d mild = jittered(c.points, 0.15 / kCells, 1);
  const CellQuality good = checkPolyMeshCells(mild, c.cells);
  EXPECT_TRUE(good.ok());
  EXPECT_GT(good.maxNonOrthogonality, 5.0);
  expectAgrees(reference(mild, c.cells), good);
  // Points moved by up to 0.6 of a cell: cells fold.
  const Eigen::MatrixX3d wild = jittered(c.points, 0.6 / kCells, 2);
  const CellQuality folded = checkPolyMeshCells(wild, c.cells);
  EXPECT_GT(folded.negativeVolumeCells, 0);
  EXPECT_GT(folded.badCells, folded.negativeVolumeCells);  // inverted face pyramids in cells of positive volume too
  expectAgrees(reference(wild, c.cells), folded);
}

TEST(CellQualitySweeps, TrianglesAndPentagonsAgreeWithOpenFoamsOwnComputation) {
  // Every 7th face a pair of triangles or a pentagon, internal and boundary.
  const Cube c = withOtherPolygons(cube(kCells), 7);
  ASSERT_GT(c.cells.faceCount(), cube(kCells).cells.faceCount());
  const Eigen::MatrixX3d mild = jittered(c.points, 0.15 / kCells, 5);
  const CellQuality good = checkPolyMeshCells(mild, c.cells);
  EXPECT_TRUE(good.ok());
  expectAgrees(reference(mild, c.cells), good);
  const Eigen::MatrixX3d wild = jittered(c.points, 0.6 / kCells, 6);
  const CellQuality folded = checkPolyMeshCells(wild, c.cells);
  EXPECT_GT(folded.badCells, 0);
  expectAgrees(reference(wild, c.cells), folded);
}

// The check reads a face's points again for its skewness only where the skewness could exceed the
// largest so far: one point moved in a regular cube, far into the last sweep, makes the few faces
// around it the most skewed, and the largest skewness is still theirs.
TEST(CellQualitySweeps, OneMovedPointInARegularCubeGivesTheLargestSkewness) {
  const Cube c = cube(kCells);
  const CellQuality regular = checkPolyMeshCells(c.points, c.cells);
  EXPECT_LT(regular.maxSkewness, 1e-12);
  Eigen::MatrixX3d moved = c.points;
  const int m = kCells + 1, i = kCells - 3, j = kCells - 4, k = kCells - 5;
  moved.row(i + m * (j + m * k)) += Eigen::RowVector3d(0.3, 0.2, -0.1) / kCells;
  const CellQuality one = checkPolyMeshCells(moved, c.cells);
  EXPECT_GT(one.maxSkewness, 0.05);
  EXPECT_TRUE(one.ok());
  // (expectAgrees would also compare the total volume, whose 157,464 equal terms the reference
  // adds in another order: about 1e-12 apart here.)
  const CellQuality expected = reference(moved, c.cells);
  EXPECT_NEAR(one.maxSkewness, expected.maxSkewness, 1e-7 * expected.maxSkewness);
  EXPECT_NEAR(one.maxNonOrthogonality, expected.maxNonOrthogonality, 1e-7);
}

TEST(CellQualitySweeps, ResultsDoNotDependOnTheThreadCountOrTheCellNumbering) {
  Cube c = cube(kCells);
  const Eigen::MatrixX3d points = jittered(c.points, 0.55 / kCells, 3);
  const CellQuality one = checkedOnOneAndTwoThreads(points, c.cells);
  EXPECT_GT(one.badCells, 0);

  // Cells numbered at random: no band, an owner above its neighbour for about half the faces, so
  // that most faces are computed again at their second cell. The same cells, so the same values.
  std::vector<std::int32_t> number(static_cast<std::size_t>(c.cells.cellCount));
  for (std::size_t i = 0; i < number.size(); ++i) number[i] = std::int32_t(i);
  std::shuffle(number.begin(), number.end(), std::mt19937(4));
  for (std::int32_t& cell : c.cells.owner.held()) cell = number[std::size_t(cell)];
  for (std::int32_t& cell : c.cells.neighbour.held()) cell = number[std::size_t(cell)];
  const CellQuality shuffled = checkPolyMeshCells(points, c.cells);
  EXPECT_TRUE(sameBits(shuffled.minVolume, one.minVolume));
  EXPECT_TRUE(sameBits(shuffled.maxVolume, one.maxVolume));
  EXPECT_TRUE(sameBits(shuffled.minPyramidVolume, one.minPyramidVolume));
  EXPECT_TRUE(sameBits(shuffled.maxNonOrthogonality, one.maxNonOrthogonality));
  EXPECT_TRUE(sameBits(shuffled.maxSkewness, one.maxSkewness));
  EXPECT_EQ(shuffled.negativeVolumeCells, one.negativeVolumeCells);
  EXPECT_EQ(shuffled.incorrectlyOrientedFaces, one.incorrectlyOrientedFaces);
  EXPECT_EQ(shuffled.badCells, one.badCells);
  expectAgrees(reference(points, c.cells), shuffled);
}

// The same cells numbered anew by `number`, their faces kept in order, or with the internal faces
// sorted by their new owners (`ownersInOrder`, stable: as OpenFOAM orders a mesh's faces, with the
// neighbours on either side of their owners).
Cube renumbered(const Cube& c, const std::vector<std::int32_t>& number, bool ownersInOrder) {
  Cube r;
  r.points = c.points;
  r.cells.cellCount = c.cells.cellCount;
  const std::int64_t internal = std::int64_t(c.cells.neighbour.size());
  std::vector<std::int64_t> order(static_cast<std::size_t>(c.cells.faceCount()));
  for (std::size_t f = 0; f < order.size(); ++f) order[f] = std::int64_t(f);
  auto ownerOf = [&](std::int64_t f) { return number[std::size_t(c.cells.owner[std::size_t(f)])]; };
  if (ownersInOrder)
    std::stable_sort(order.begin(), order.begin() + internal, [&](std::int64_t a, std::int64_t b) { return ownerOf(a) < ownerOf(b); });
  r.cells.faceStarts = {0};
  for (std::int64_t f : order) {
    for (std::int32_t k = c.cells.faceStarts[std::size_t(f)]; k < c.cells.faceStarts[std::size_t(f) + 1]; ++k)
      r.cells.faceVertices.push_back(c.cells.faceVertices[std::size_t(k)]);
    r.cells.faceStarts.push_back(std::int32_t(r.cells.faceVertices.size()));
    r.cells.owner.push_back(ownerOf(f));
    if (f < internal) r.cells.neighbour.push_back(number[std::size_t(c.cells.neighbour[std::size_t(f)])]);
  }
  return r;
}

// The check makes its cell-to-face lists sweep by sweep where the internal faces come in their
// owners' order and the bandwidth is small, and keeps a window of cell centres where the bandwidth
// is small, else each for the whole mesh: cells renumbered within runs of 300 (a small bandwidth,
// neighbours on either side) with the faces in their old order (whole-mesh lists, a window of
// centres) or sorted by owner (lists by sweep, a window), and renumbered at random with the faces
// sorted by owner (a bandwidth of about the mesh: whole-mesh lists and centres), each agree with
// OpenFOAM's computation, and on one thread and on two bit for bit.
TEST(CellQualitySweeps, EveryCellNumberingAndFaceOrderAgreesWithOpenFoamsOwnComputation) {
  const Cube c = cube(kCells);
  std::vector<std::int32_t> local(static_cast<std::size_t>(c.cells.cellCount)), random;
  for (std::size_t i = 0; i < local.size(); ++i) local[i] = std::int32_t(i);
  random = local;
  std::mt19937 rng(8);
  for (std::size_t i = 0; i < local.size(); i += 300) std::shuffle(local.begin() + std::ptrdiff_t(i), local.begin() + std::ptrdiff_t(std::min(local.size(), i + 300)), rng);
  std::shuffle(random.begin(), random.end(), rng);
  const Eigen::MatrixX3d points = jittered(c.points, 0.55 / kCells, 9);
  // OpenFOAM's computation of the same cells in any numbering: the same values (to rounding: its
  // cell sums follow the face order), the same bad cells under their new numbers.
  std::vector<std::int64_t> badCells;
  const CellQuality blockMeshOrder = reference(points, c.cells, &badCells);
  for (const auto& [number, ownersInOrder] : {std::pair{&local, false}, {&local, true}, {&random, true}}) {
    const Cube r = renumbered(c, *number, ownersInOrder);
    const CellQuality one = checkedOnOneAndTwoThreads(points, r.cells);
    EXPECT_GT(one.badCells, 0);
    CellQuality expected = blockMeshOrder;
    std::vector<std::int64_t> renumberedBad;
    for (std::int64_t cell : badCells) renumberedBad.push_back((*number)[std::size_t(cell)]);
    std::sort(renumberedBad.begin(), renumberedBad.end());
    expected.firstBadCells.assign(renumberedBad.begin(), renumberedBad.begin() + std::min<std::ptrdiff_t>(10, std::ssize(renumberedBad)));
    expectAgrees(expected, one);
  }
}

}  // namespace
}  // namespace ffdkit::meshio
