#include "ffdkit/geometry/curvenet/network_tessellation.h"

#include <algorithm>
#include <cstring>
#include <deque>
#include <map>
#include <stdexcept>
#include <string>
#include <tuple>

namespace ffdkit::geometry::curvenet {
namespace {

long long bits(double x) {
  long long b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

int latticeIndex(int n, int r, int k, int j) {
  if (r == 0) return 0;
  if (j == r) {  // (r, r)_k is (r, 0)_{k+1}
    k = (k + 1) % n;
    j = 0;
  }
  return 1 + n * r * (r - 1) / 2 + k * r + j;
}

}  // namespace

NGonLattice ngonLattice(const NGonDomain& domain, int pitch) {
  if (pitch < 1) throw std::invalid_argument("tessellation pitch must be >= 1, got " + std::to_string(pitch));
  const int n = domain.sides();
  NGonLattice lattice;
  lattice.points.resize(1 + n * pitch * (pitch + 1) / 2, 2);
  lattice.points.row(0).setZero();
  for (int r = 1; r <= pitch; ++r) {
    for (int k = 0; k < n; ++k) {
      for (int j = 0; j < r; ++j) {
        const double f = static_cast<double>(j) / r;
        lattice.points.row(latticeIndex(n, r, k, j)) =
            (static_cast<double>(r) / pitch * ((1.0 - f) * domain.vertex(k) + f * domain.vertex(k + 1))).transpose();
      }
    }
  }
  lattice.triangles.resize(n * pitch * pitch, 3);
  int t = 0;
  for (int k = 0; k < n; ++k) {
    for (int r = 1; r <= pitch; ++r) {
      for (int j = 0; j < r; ++j) {
        lattice.triangles.row(t++) << latticeIndex(n, r - 1, k, j), latticeIndex(n, r, k, j),
            latticeIndex(n, r, k, j + 1);
        if (j < r - 1) {
          lattice.triangles.row(t++) << latticeIndex(n, r - 1, k, j), latticeIndex(n, r, k, j + 1),
              latticeIndex(n, r - 1, k, j + 1);
        }
      }
    }
  }
  return lattice;
}

NetworkMesh tessellateNetwork(const CurveNetwork& net, int pitch, const PatchOptions& options) {
  if (pitch < 1) throw std::invalid_argument("tessellation pitch must be >= 1, got " + std::to_string(pitch));
  using Key = std::tuple<int, int, long long, long long, int>;
  std::map<Key, int> welded;
  std::vector<Eigen::Vector3d> positions, normals;
  std::map<int, std::vector<std::pair<double, int>>> onRun;  // run -> (u~, vertex)
  std::vector<Eigen::Vector3i> triangles;
  std::vector<int> triangleFace;
  auto addVertex = [&](const Key& key, auto&& make) {
    const auto it = welded.find(key);
    if (it != welded.end()) return it->second;
    Eigen::Vector3d p, nrm;
    make(p, nrm);
    positions.push_back(p);
    normals.push_back(nrm);
    const int id = static_cast<int>(positions.size()) - 1;
    welded.emplace(key, id);
    return id;
  };
  auto registerOnRun = [&](int run, double u, int vertex) {
    auto& list = onRun[run];
    for (const auto& e : list) {
      if (e.second == vertex) return;
    }
    list.push_back({u, vertex});
  };
  std::map<int, NGonDomain> domains;
  std::map<int, NGonLattice> lattices;
  for (int f = 0; f < static_cast<int>(net.faces.size()); ++f) {
    const Face& face = net.faces[f];
    const int n = static_cast<int>(face.sides.size());
    if (!domains.count(n)) {
      domains.emplace(n, NGonDomain(n));
      lattices.emplace(n, ngonLattice(domains.at(n), pitch));
    }
    const NGonDomain& domain = domains.at(n);
    const NGonLattice& lattice = lattices.at(n);
    std::vector<int> map(lattice.points.rows(), -1);
    auto patchAt = [&](const Eigen::Vector2d& p) { return evaluatePatch(net, f, domain, p, options); };
    for (int k = 0; k < n; ++k) {
      const FaceSide& side = face.sides[k];
      if (side.run < 0) {
        // Virtual side of an open region: a free boundary of this face only.
        for (int j = 0; j < pitch; ++j) {
          const int row = latticeIndex(n, pitch, k, j);
          const Eigen::Vector2d p = lattice.points.row(row).transpose();
          const Key key = j == 0 ? Key{0, side.startVertex, 0, 0, 0} : Key{4, f, k, 0, j};
          map[row] = addVertex(key, [&](Eigen::Vector3d& pos, Eigen::Vector3d& nrm) {
            pos = j == 0 ? net.vertices[side.startVertex].position : patchAt(p).v;
            nrm = patchNormal(patchAt(j == 0 ? Eigen::Vector2d(p * (1.0 - 1e-6)) : p));
          });
        }
        continue;
      }
      const Run& run = net.runs[side.run];
      const bool full = side.rho0 == 0.0 && side.rho1 == 1.0;
      const double span = side.rho1 - side.rho0;
      for (int j = 0; j < pitch; ++j) {
        const int row = latticeIndex(n, pitch, k, j);
        const Eigen::Vector2d p = lattice.points.row(row).transpose();
        double u = 0.0;
        Key key;
        if (full) {
          const int jRun = side.forward ? j : pitch - j;
          u = static_cast<double>(jRun) / pitch;
          key = {1, side.run, 0, 0, jRun};
        } else {
          u = side.forward ? side.rho0 + span * j / pitch : side.rho1 - span * j / pitch;
          key = {2, side.run, bits(side.rho0), bits(side.rho1), side.forward ? j : pitch - j};
        }
        if (j == 0 && side.startVertex >= 0) {
          key = {0, side.startVertex, 0, 0, 0};
        } else if (j == 0) {
          key = {3, side.run, bits(u), 0, 0};
        }
        const int id = addVertex(key, [&](Eigen::Vector3d& pos, Eigen::Vector3d& nrm) {
          if (j == 0 && side.startVertex >= 0) {
            pos = net.vertices[side.startVertex].position;
            nrm = net.vertices[side.startVertex].normal;
            // Free ends (open-region corners) have no tangent plane: take it just inside.
            if (net.vertices[side.startVertex].kind == NetworkVertex::Kind::FreeEnd) {
              nrm = patchNormal(patchAt(p * (1.0 - 1e-6)));
            }
            return;
          }
          pos = net.curves[run.curve].evaluate(run.tStart + run.delta() * u);
          if (j == 0) {
            // A two-curve-region midpoint is a domain vertex: take the normal just inside.
            nrm = patchNormal(patchAt(p * (1.0 - 1e-6)));
          } else {
            nrm = patchNormal(patchAt(p));
          }
        });
        map[row] = id;
        registerOnRun(side.run, u, id);
        if (j == 0) {
          const FaceSide& prev = face.sides[(k - 1 + n) % n];
          if (prev.run >= 0) registerOnRun(prev.run, prev.forward ? prev.rho1 : prev.rho0, id);
        }
      }
    }
    for (int row = 0; row < lattice.points.rows(); ++row) {
      if (map[row] >= 0) continue;
      const VectorJet q = patchAt(lattice.points.row(row).transpose());
      positions.push_back(q.v);
      normals.push_back(patchNormal(q));
      map[row] = static_cast<int>(positions.size()) - 1;
    }
    for (int t = 0; t < lattice.triangles.rows(); ++t) {
      triangles.emplace_back(map[lattice.triangles(t, 0)], map[lattice.triangles(t, 1)],
                             map[lattice.triangles(t, 2)]);
      triangleFace.push_back(f);
    }
  }
  // Remove T-vertices: split a triangle whose edge lies on a run that another face sampled
  // more finely (Kuriyama 1996, sec. 5.3.4 "zipper-stitch").
  std::map<int, std::vector<std::pair<int, double>>> runsOfVertex;
  for (auto& [run, list] : onRun) {
    std::sort(list.begin(), list.end());
    for (const auto& [u, v] : list) runsOfVertex[v].push_back({run, u});
  }
  std::vector<Eigen::Vector3i> finalTriangles;
  std::vector<int> finalFace;
  std::deque<std::pair<Eigen::Vector3i, int>> queue;
  for (std::size_t t = 0; t < triangles.size(); ++t) queue.push_back({triangles[t], triangleFace[t]});
  while (!queue.empty()) {
    const auto [tri, face] = queue.front();
    queue.pop_front();
    bool split = false;
    for (int e = 0; e < 3 && !split; ++e) {
      const int a = tri[e], b = tri[(e + 1) % 3], c = tri[(e + 2) % 3];
      const auto ia = runsOfVertex.find(a), ib = runsOfVertex.find(b);
      if (ia == runsOfVertex.end() || ib == runsOfVertex.end()) continue;
      for (const auto& [runA, uA] : ia->second) {
        for (const auto& [runB, uB] : ib->second) {
          if (runA != runB || split) continue;
          const double lo = std::min(uA, uB), hi = std::max(uA, uB);
          std::vector<std::pair<double, int>> between;
          for (const auto& [u, v] : onRun[runA]) {
            if (u > lo && u < hi && v != a && v != b) between.push_back({u, v});
          }
          if (between.empty()) continue;
          if (uA > uB) std::reverse(between.begin(), between.end());
          int prev = a;
          for (const auto& [u, v] : between) {
            queue.push_back({Eigen::Vector3i(prev, v, c), face});
            prev = v;
          }
          queue.push_back({Eigen::Vector3i(prev, b, c), face});
          split = true;
        }
      }
    }
    if (!split) {
      finalTriangles.push_back(tri);
      finalFace.push_back(face);
    }
  }
  NetworkMesh out;
  out.mesh.vertices.resize(positions.size(), 3);
  out.normals.resize(positions.size(), 3);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    out.mesh.vertices.row(i) = positions[i].transpose();
    out.normals.row(i) = normals[i].transpose();
  }
  out.mesh.triangles.resize(finalTriangles.size(), 3);
  for (std::size_t t = 0; t < finalTriangles.size(); ++t) out.mesh.triangles.row(t) = finalTriangles[t].transpose();
  out.triangleFace = finalFace;
  return out;
}

}  // namespace ffdkit::geometry::curvenet
