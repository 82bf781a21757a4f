#include "g3_test_data.h"

#include <algorithm>

namespace ffdkit::geometry::g3::testdata {
namespace {
Eigen::MatrixX2d rows(std::initializer_list<double> xy) {
  Eigen::MatrixX2d m(static_cast<Eigen::Index>(xy.size() / 2), 2);
  Eigen::Index k = 0;
  for (double value : xy) {
    m(k / 2, k % 2) = value;
    ++k;
  }
  return m;
}
}  // namespace

Eigen::MatrixX2d figure2Points() {
  return rows({0.6, 10.5, 4, 11.2, 7.2, 7.9, 10.6, 5.7, 13.9, 8.9, 16.3, 14, 19.8, 17.4, 23.3, 16.6});
}
Eigen::MatrixX2d figure3Points() {
  return rows({11.5, 6.4, 5.2, 2.6, 2, 1.6, 1.2, 5, 5.3, 4.7, 9.1, 1.3, 9.5, 2.9, 7, 5.7, 12.5, 5.7, 12.5, 3.7, 10.5, 3.2});
}
Eigen::MatrixX2d figure4Points() {
  return rows({5.44,  14.16, 7.59,  15.88,  10.12, 16.9,   12.87, 16.86, 15.16, 15.34, 15.92, 12.69, 14.305,
               10.465, 11.55, 10.35, 9.35,  11.99, 7.86,   14.3,   5.615, 15.9,  3,     15.075, 1.55,  12.75,
               1.61,  10,    2.79,  7.5,    4.8,   5.61,   7.395,  4.66,  10.12, 5.035, 12.045, 7.03,  12.5,
               9.75,  12.3,  12.48});
}
Eigen::MatrixX2d figure5Points() {
  return rows({6, 2, 3.5, 7.5, 8, 11, 11.5, 8.5, 9.5, 4.5, 6, 9, 6, 15, 13, 17.5, 20.5, 13, 17.5, 7, 14.5, 2, 20, 1});
}

double s1Angle(double s) { return 0.3 - 0.25 * s + 0.03 * s * s - 0.001 * s * s * s; }
double s1Curvature(double s) { return -0.25 + 0.06 * s - 0.003 * s * s; }
double s1CurvatureDerivative(double s) { return 0.06 - 0.006 * s; }
Eigen::VectorXd s1Knots() {
  Eigen::VectorXd k(7);
  k << 0, 1.5, 3.2, 5.0, 6.1, 8.3, 10;
  return k;
}
Eigen::MatrixX2d s1Points() {
  return rows({1, 2, 2.480543431041, 2.199799079088, 4.163114383734, 1.981049034748, 5.889865502878,
               1.475446358848, 6.929420706210, 1.115846573082, 9.021114662228, 0.435055035506, 10.671427113806,
               0.028970616071});
}

Eigen::VectorXd cubicDeBoor(const Eigen::Vector4d& c, const Eigen::VectorXd& knots) {
  const int n = static_cast<int>(knots.size()) - 1;
  auto knot = [&](int j) { return knots[std::clamp(j, 0, n)]; };
  Eigen::VectorXd d(n + 3);
  for (int j = -1; j <= n + 1; ++j) {
    const double u1 = knot(j - 1), u2 = knot(j), u3 = knot(j + 1);
    d[j + 1] = c[0] + c[1] * (u1 + u2 + u3) / 3.0 + c[2] * (u1 * u2 + u1 * u3 + u2 * u3) / 3.0 + c[3] * u1 * u2 * u3;
  }
  return d;
}

}  // namespace ffdkit::geometry::g3::testdata
