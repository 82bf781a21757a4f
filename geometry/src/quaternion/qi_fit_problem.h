#pragma once

// Internal to qi_fitting.cpp: the least-squares problem of a QI chain fit at fixed parameters u_i
// (Sakiyama et al. 2001, eq. (19)), its residual and its Jacobian. Everything that does not depend
// on the design vector (quadrature nodes and weights, cumulative Bernstein values at the nodes,
// where each data point closes its integral) is computed once per fit; an evaluation keeps the
// per-node rotations, so the Jacobian of an accepted step reuses them instead of integrating again.

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ffdkit/geometry/quaternion/cumulative_bezier_quaternion.h"
#include "ffdkit/geometry/quaternion/qi_chain.h"

namespace ffdkit::geometry::quaternion::detail {

/// The design vector, segment-major (Sakiyama et al. 2001, sec. 3.5): [eta (startVars) |
/// w_01..w_0k, lambda_0 | ...], l = exp(lambda); planar w_ij = phi_ij e_z.
struct QiFitLayout {
  int segments = 0;
  int degree = 2;
  bool planar = false;
  int startVars = 0;  ///< 0, 1 (planar Free start tangent) or 2 (spatial Free)
  int omegaDim() const { return planar ? 1 : 3; }
  int segmentVars() const { return degree * omegaDim() + 1; }
  int offset(int seg) const { return startVars + seg * segmentVars(); }
  int size() const { return offset(segments); }
};

/// State of one design vector: residual r (3 #P, point-major: C(u_i) - P_i), segment start points
/// and orientations (segments + 1), and the per-node rotations E_j of the quadrature.
struct QiFitEvaluation {
  Eigen::VectorXd r;
  std::vector<Eigen::Vector3d> p;
  std::vector<Eigen::Quaterniond> q;
  std::vector<Eigen::Quaterniond> e;  ///< node-major, degree per node, all segments
  std::vector<Eigen::Vector3d> t;     ///< unit tangent per node
};

class QiFitProblem {
 public:
  /// points: #P x 3; breaks 0 = b_0 < ... < b_M = #P - 1; u: #P parameters with u_{b_j} = j.
  QiFitProblem(const Eigen::MatrixX3d& points, const std::vector<int>& breaks, const Eigen::VectorXd& u,
               QiFitLayout layout, ProductForm form, QiQuadrature quadrature, const Eigen::Vector3d& start,
               const Eigen::Quaterniond& baseQ00, const Eigen::Vector3d& freeAxis1, const Eigen::Vector3d& freeAxis2);

  const QiFitLayout& layout() const { return layout_; }
  int size() const { return layout_.size(); }
  std::vector<Eigen::Vector3d> omegas(const Eigen::VectorXd& x, int seg) const;
  double length(const Eigen::VectorXd& x, int seg) const;
  Eigen::Quaterniond q00(const Eigen::VectorXd& x) const;

  /// Residual of the whole chain.
  void evaluate(const Eigen::VectorXd& x, QiFitEvaluation& ev) const;
  /// Residual rows of the points of segments >= from, from the start state ev.p[from], ev.q[from];
  /// rows of earlier segments are left as they are.
  void evaluateFrom(const Eigen::VectorXd& x, int from, QiFitEvaluation& ev) const;
  /// Gauss-Newton normal equations of the exact Jacobian J at the x that `ev` was evaluated at:
  /// a = J^T J (size x size), g = J^T r. J follows by the chain rule through the frame rotations (left
  /// Jacobians of SO(3)) and is never formed: the rows of a point i of segment s are [M_i D_s | O_i],
  /// with D_s the derivative of the segment's start point and orientation (6 x the variables of
  /// earlier segments), M_i = [I | G_i] (3 x 6) and O_i the segment's own columns. D moves from
  /// segment to segment by a 6 x 6 map A_s, so the rows of all later segments reach a segment's
  /// variables through one 6 x 6 matrix, summed from the last segment back (later[s] = S_s +
  /// A_s^T later[s + 1] A_s, S_s = sum_i M_i^T M_i); each block of J^T J is then one product with
  /// the columns of D: about 3 size^2 multiply-adds for a (D_s^T S_s D_s per segment took about
  /// size^2 times the number of segments).
  void analyticNormalEquations(const Eigen::VectorXd& x, const QiFitEvaluation& ev, Eigen::MatrixXd& a,
                               Eigen::VectorXd& g) const;
  /// Forward differences, sqrt(eps) relative steps; a column of segment s recomputes segments >= s
  /// only (Sakiyama et al. 2001, sec. 3.5.1). @return the number of partial evaluations.
  int finiteDifferenceJacobian(const Eigen::VectorXd& x, const QiFitEvaluation& ev, Eigen::MatrixXd& j) const;
  /// Residual rows [begin, end) of the points of segment seg (a break point belongs to the later one).
  int rowBegin(int seg) const { return 3 * firstPoint(seg); }
  int rowEnd(int seg) const { return 3 * (lastPoint(seg) + 1); }
  const Eigen::Vector3d& start() const { return start_; }
  ProductForm form() const { return form_; }
  const QiQuadrature& quadrature() const { return quadrature_; }
  /// Run the per-segment sweeps of evaluate and analyticNormalEquations on the OpenMP threads (on by
  /// default; they start only for fits of at least kParallelNodes nodes). The results are the same
  /// bits with any thread count: each segment is computed alone, and the chain combines them in order.
  void setParallel(bool parallel) { parallel_ = parallel; }
  static constexpr int kParallelNodes = 512;

  /// Chooses, call by call, between the threaded and the serial sweep by their measured times. A
  /// sweep takes 50-150 us, so on a machine whose cores are busy a thread that waits for a core
  /// stalls the whole region (milliseconds per region on 2 busy cores, against 50-75 us
  /// serial). Both ways give the same bits, so the choice only moves time: the first sweep of a fit
  /// is serial, then threaded with a serial one every 16 calls; two threaded sweeps slower than the
  /// serial one switch threads off for the rest of the fit and, for all fits, for one second. (With
  /// OMP_WAIT_POLICY=passive each region waits for its threads to wake: the spiral's 30-60 us sweeps
  /// took 10.7 ms per fit on 2 threads against 9.4 ms serial; the rule was 3x the serial time.)
  class SweepGovernor {
   public:
    bool threaded() const;
    void record(bool threaded, double seconds);

   private:
    double serialSeconds_ = -1.0;
    int calls_ = 0;
    int strikes_ = 0;
    bool off_ = false;
  };

 private:
  struct SegmentPlan {
    std::vector<double> weight;  ///< Gauss-Legendre weight times half the panel width, per node
    std::vector<double> basis;   ///< ~B_{j,k}(t) at each node, node-major (degree per node)
    std::vector<int> closeAfter; ///< per output (data points lo..hi, then u = 1): nodes integrated before it
    int firstNode = 0;           ///< index of this segment's first node in QiFitEvaluation::e / t
  };
  /// One segment's share of the normal equations (its node sweep); the chain in
  /// analyticNormalEquations combines them with D.
  struct SegmentNormalSums {
    Eigen::Matrix<double, 6, 6> s66;
    Eigen::Matrix<double, 6, Eigen::Dynamic> c6;
    Eigen::MatrixXd oo;
    Eigen::Matrix<double, 6, 1> b6;
    Eigen::VectorXd gOwn;
    Eigen::Matrix3d gl;                       ///< G of the segment's end point
    Eigen::Matrix<double, 3, Eigen::Dynamic> own;  ///< own columns of the segment's end point
  };
  /// The node sweep of one segment from its start orientation ev.q[seg]: rotations, tangents, and
  /// positions relative to the segment's start point (residual rows l int t, end point in ev.p[seg + 1]).
  void sweepSegment(const Eigen::VectorXd& x, int seg, QiFitEvaluation& ev) const;
  void segmentNormalSums(const Eigen::VectorXd& x, const QiFitEvaluation& ev, int seg, SegmentNormalSums& out) const;
  /// How a segment carries D (derivatives of its start point and orientation, 6 x variables) to its
  /// end: the columns of earlier variables become a D (a = [I G; 0 R], G of the end point, R the
  /// segment's rotation in form A, I in form B), its own variables enter as `columns` (6 x sv).
  struct SegmentTransfer {
    Eigen::Matrix<double, 6, 6> a;
    Eigen::Matrix3d rotation;
    Eigen::Matrix<double, 6, Eigen::Dynamic> columns;
  };
  void segmentTransfer(const Eigen::VectorXd& x, const QiFitEvaluation& ev, int seg, const SegmentNormalSums& sums,
                       SegmentTransfer& out) const;
  /// The same with the degree fixed at compile time (K = 2, 3) or read from the layout (K = 0).
  template <int K>
  void sweepSegmentOfDegree(const Eigen::VectorXd& x, int seg, QiFitEvaluation& ev) const;
  template <int K>
  void segmentNormalSumsOfDegree(const Eigen::VectorXd& x, const QiFitEvaluation& ev, int seg,
                                 SegmentNormalSums& out) const;
  int firstPoint(int seg) const { return breaks_[seg]; }
  int lastPoint(int seg) const { return seg + 1 == layout_.segments ? breaks_[seg + 1] : breaks_[seg + 1] - 1; }

  const Eigen::MatrixX3d& points_;
  std::vector<int> breaks_;
  QiFitLayout layout_;
  ProductForm form_;
  QiQuadrature quadrature_;
  Eigen::Vector3d start_;
  Eigen::Quaterniond baseQ00_;
  Eigen::Vector3d freeAxis1_, freeAxis2_;
  std::vector<SegmentPlan> plans_;
  int nodes_ = 0;
  bool parallel_ = true;
  mutable SweepGovernor evaluationGovernor_, normalGovernor_;
};

}  // namespace ffdkit::geometry::quaternion::detail
