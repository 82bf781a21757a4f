#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ffdkit::geometry::quaternion {

/// Order of the cumulative exponential product (Sakiyama et al. 2001, sec. 2.2). The two forms
/// coincide when all angular-derivative vectors are parallel (e.g. planar curves) and differ
/// otherwise.
enum class ProductForm {
  Global,  ///< q(t) = exp(w_n ~B_n) ... exp(w_1 ~B_1) q_0 ("form A", Sakiyama et al. 2001, sec. 2.2, normative there)
  Local,   ///< q(t) = q_0 exp(w_1 ~B_1) ... exp(w_n ~B_n) (Kim et al., "form B", Sphere-tangent report, eq. (14))
};

/// Kim-Kim-Shin's cumulative Bezier unit quaternion curve of degree n on t in [0, 1]:
/// a product of exponentials of the angular-derivative vectors w_i weighted by the cumulative
/// Bernstein basis. It is NOT Shoemake's slerp / de Casteljau curve (Sphere-tangent report,
/// sec. 3.2). q(0) = q_0; q(1) = the last control. @see Sphere-tangent report, sec. 3.2, eqs. (13)-(15);
/// Sakiyama et al. 2001, sec. 2.2.
class CumulativeBezierQuaternion {
 public:
  /// q0: start quaternion (used as given, not normalised); omegas: w_1..w_n (n >= 1).
  /// @throws QuaternionCurveError if omegas is empty.
  CumulativeBezierQuaternion(const Eigen::Quaterniond& q0, std::vector<Eigen::Vector3d> omegas,
                             ProductForm form = ProductForm::Local);

  /// From control quaternions q_0..q_n (n >= 1): w_i = log(q_{i-1}^-1 q_i) (Local) or
  /// log(q_i q_{i-1}^-1) (Global). @throws QuaternionCurveError if a log is undefined (e.g.
  /// antipodal neighbouring pure controls) or fewer than 2 controls.
  static CumulativeBezierQuaternion fromControls(const std::vector<Eigen::Quaterniond>& controls,
                                                 ProductForm form = ProductForm::Local);

  /// Degree, the number of angular-derivative vectors.
  int degree() const { return static_cast<int>(omegas_.size()); }
  /// Global or local product form.
  ProductForm form() const { return form_; }
  /// The start orientation q0.
  const Eigen::Quaterniond& start() const { return q0_; }
  /// The angular-derivative vectors omega_1..omega_k.
  const std::vector<Eigen::Vector3d>& omegas() const { return omegas_; }

  /// q(t).
  Eigen::Quaterniond value(double t) const;
  /// dq/dt, analytic (Sphere-tangent report, sec. 3.2): sum over i of the product with (0, w_i
  /// ~B_i'(t)) inserted at factor i.
  Eigen::Quaterniond derivative(double t) const;
  /// q(t) and dq/dt in one pass.
  void evaluate(double t, Eigen::Quaterniond& q, Eigen::Quaterniond& dq) const;
  /// q(1) = the end control.
  Eigen::Quaterniond end() const { return value(1.0); }

 private:
  Eigen::Quaterniond q0_;
  std::vector<Eigen::Vector3d> omegas_;
  ProductForm form_;
};

}  // namespace ffdkit::geometry::quaternion
