#include "ffdkit/geometry/quaternion/cumulative_bezier_quaternion.h"

#include <sstream>

#include "ffdkit/geometry/quaternion/bernstein.h"
#include "ffdkit/geometry/quaternion/quaternion_error.h"
#include "ffdkit/geometry/quaternion/unit_quaternion.h"

namespace ffdkit::geometry::quaternion {

CumulativeBezierQuaternion::CumulativeBezierQuaternion(const Eigen::Quaterniond& q0, std::vector<Eigen::Vector3d> omegas,
                                                       ProductForm form)
    : q0_(q0), omegas_(std::move(omegas)), form_(form) {
  if (omegas_.empty()) {
    throw QuaternionCurveError("CumulativeBezierQuaternion: expected at least one angular-derivative vector, got 0");
  }
}

CumulativeBezierQuaternion CumulativeBezierQuaternion::fromControls(const std::vector<Eigen::Quaterniond>& controls,
                                                                     ProductForm form) {
  if (controls.size() < 2) {
    std::ostringstream msg;
    msg << "CumulativeBezierQuaternion::fromControls: expected at least 2 controls, got " << controls.size();
    throw QuaternionCurveError(msg.str());
  }
  std::vector<Eigen::Vector3d> omegas;
  for (std::size_t i = 1; i < controls.size(); ++i) {
    const Eigen::Quaterniond rel = form == ProductForm::Local ? controls[i - 1].conjugate() * controls[i]
                                                              : controls[i] * controls[i - 1].conjugate();
    try {
      omegas.push_back(quaternionLog(rel));
    } catch (const QuaternionCurveError&) {
      std::ostringstream msg;
      msg << "CumulativeBezierQuaternion::fromControls: controls " << i - 1 << " and " << i
          << " are antipodal (relative rotation by 2 pi): the angular-derivative vector is undefined";
      throw QuaternionCurveError(msg.str());
    }
  }
  return CumulativeBezierQuaternion(controls.front(), std::move(omegas), form);
}

Eigen::Quaterniond CumulativeBezierQuaternion::value(double t) const {
  const int n = degree();
  Eigen::Quaterniond q = q0_;
  for (int j = 1; j <= n; ++j) {
    const Eigen::Quaterniond e = quaternionExp(omegas_[j - 1] * cumulativeBernstein(n, j, t));
    q = form_ == ProductForm::Local ? Eigen::Quaterniond(q * e) : Eigen::Quaterniond(e * q);
  }
  return q;
}

Eigen::Quaterniond CumulativeBezierQuaternion::derivative(double t) const {
  Eigen::Quaterniond q, dq;
  evaluate(t, q, dq);
  return dq;
}

void CumulativeBezierQuaternion::evaluate(double t, Eigen::Quaterniond& q, Eigen::Quaterniond& dq) const {
  const int n = degree();
  std::vector<Eigen::Quaterniond> e(n + 1), prefix(n + 1), suffix(n + 1);
  for (int j = 1; j <= n; ++j) e[j] = quaternionExp(omegas_[j - 1] * cumulativeBernstein(n, j, t));
  prefix[0] = q0_;
  suffix[n] = Eigen::Quaterniond::Identity();
  dq = Eigen::Quaterniond(0.0, 0.0, 0.0, 0.0);
  if (form_ == ProductForm::Local) {
    // q = q0 E1..En; dq = sum_j (q0 E1..Ej) (0, w_j ~B_j') (E_{j+1}..En).
    for (int j = 1; j <= n; ++j) prefix[j] = prefix[j - 1] * e[j];
    for (int j = n; j >= 1; --j) suffix[j - 1] = e[j] * suffix[j];
    for (int j = 1; j <= n; ++j) {
      const Eigen::Quaterniond d = pureQuaternion(omegas_[j - 1] * cumulativeBernsteinDerivative(n, j, t));
      dq.coeffs() += (prefix[j] * d * suffix[j]).coeffs();
    }
  } else {
    // q = En..E1 q0; dq = sum_j (En..E_{j+1}) (0, w_j ~B_j') (Ej..E1 q0).
    for (int j = 1; j <= n; ++j) prefix[j] = e[j] * prefix[j - 1];
    for (int j = n; j >= 1; --j) suffix[j - 1] = suffix[j] * e[j];
    for (int j = 1; j <= n; ++j) {
      const Eigen::Quaterniond d = pureQuaternion(omegas_[j - 1] * cumulativeBernsteinDerivative(n, j, t));
      dq.coeffs() += (suffix[j] * d * prefix[j]).coeffs();
    }
  }
  q = prefix[n];
}

}  // namespace ffdkit::geometry::quaternion
