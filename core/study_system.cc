#include "core/study_system.h"

#include <Eigen/Geometry>

namespace hexcal {
namespace {

// Plain bilinear cross product: Eigen's cross() conjugates complex results,
// which would break the holomorphy the homotopy relies on.
CVector3 Cross(const CVector3& u, const CVector3& v) {
  return CVector3(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
}
Complex Dot(const CVector3& u, const CVector3& v) { return u.transpose() * v; }  // bilinear

// w(A) such that tr(Aᵀ [ev]x) = ev·w.
CVector3 SkewPart(const CMatrix3& a) { return CVector3(a(2, 1) - a(1, 2), a(0, 2) - a(2, 0), a(1, 0) - a(0, 1)); }

}  // namespace

LegCoefficients CoefficientsOf(const CVector3& a, const CVector3& b, const Complex& d2) {
  return {Dot(a, a) + Dot(b, b) - d2, a, b, a * b.transpose()};
}

LegCoefficients CoefficientDerivative(const CVector3& a, const CVector3& b, const CVector3& da, const CVector3& db,
                                      const Complex& dd2) {
  return {2.0 * Dot(a, da) + 2.0 * Dot(b, db) - dd2, da, db, da * b.transpose() + a * db.transpose()};
}

Complex LegLinearPart(const LegCoefficients& c, const CVector8& z, CVector3*) {
  const Complex e0 = z[0], g0 = z[4];
  const CVector3 ev = z.segment<3>(1), gv = z.segment<3>(5);
  const Complex delta = e0 * e0 + Dot(ev, ev);
  // tr(Aᵀ M(e)) = (e0² - ev·ev) tr A + 2 evᵀ A ev + 2 e0 ev·w(A)
  const Complex trace_am = (e0 * e0 - Dot(ev, ev)) * c.ab.trace() + 2.0 * Complex(ev.transpose() * c.ab * ev) +
                           2.0 * e0 * Dot(ev, SkewPart(c.ab));
  return c.d * delta - 4.0 * g0 * Dot(c.b, ev) + 4.0 * e0 * Dot(c.b, gv) - 4.0 * Dot(c.b, Cross(ev, gv)) -
         2.0 * trace_am + 4.0 * g0 * Dot(c.a, ev) - 4.0 * e0 * Dot(c.a, gv) + 4.0 * Dot(c.a, Cross(gv, ev));
}

void LegLinearPartGradient(const LegCoefficients& c, const CVector8& z, Eigen::Matrix<Complex, 1, 8>* grad) {
  const Complex e0 = z[0], g0 = z[4];
  const CVector3 ev = z.segment<3>(1), gv = z.segment<3>(5);
  const Complex tr = c.ab.trace();
  const CVector3 w = SkewPart(c.ab);
  const Complex dtrace_de0 = 2.0 * e0 * tr + 2.0 * Dot(ev, w);
  const CVector3 dtrace_dev = -2.0 * tr * ev + 2.0 * (c.ab + c.ab.transpose()) * ev + 2.0 * e0 * w;

  (*grad)(0) = 2.0 * c.d * e0 + 4.0 * Dot(c.b, gv) - 2.0 * dtrace_de0 - 4.0 * Dot(c.a, gv);
  grad->segment<3>(1) = (2.0 * c.d * ev - 4.0 * g0 * c.b - 4.0 * Cross(gv, c.b) - 2.0 * dtrace_dev + 4.0 * g0 * c.a +
                         4.0 * Cross(c.a, gv))
                            .transpose();
  (*grad)(4) = -4.0 * Dot(c.b, ev) + 4.0 * Dot(c.a, ev);
  grad->segment<3>(5) = (4.0 * e0 * c.b - 4.0 * Cross(c.b, ev) - 4.0 * e0 * c.a + 4.0 * Cross(ev, c.a)).transpose();
}

void EvaluateStudySystem(const std::array<LegCoefficients, 6>& legs, const CVector8& chart, const CVector8& z,
                         CVector8* f, CMatrix8* jacobian) {
  const CVector8 g_part = (CVector8() << 0, 0, 0, 0, z.segment<4>(4)).finished();
  const Complex gg = Complex(z.segment<4>(4).transpose() * z.segment<4>(4));
  for (int i = 0; i < 6; ++i) {
    if (f) (*f)[i] = 4.0 * gg + LegLinearPart(legs[i], z);
    if (jacobian) {
      Eigen::Matrix<Complex, 1, 8> grad;
      LegLinearPartGradient(legs[i], z, &grad);
      jacobian->row(i) = grad + 8.0 * g_part.transpose();
    }
  }
  // Study quadric e0 g0 + ev·gv.
  if (f) {
    (*f)[6] = Complex(z.segment<4>(0).transpose() * z.segment<4>(4));
    (*f)[7] = Complex(chart.transpose() * z) - 1.0;
  }
  if (jacobian) {
    jacobian->row(6) << z.segment<4>(4).transpose(), z.segment<4>(0).transpose();
    jacobian->row(7) = chart.transpose();
  }
}

CVector8 StudyFromPose(const Pose& pose) {
  Eigen::Quaterniond q(pose.rotation);
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d ev = q.vec(), t = pose.position;
  // g = ½ (0, t) ⊗ (e0, ev) = ½ (-t·ev, e0 t + t × ev)
  const Eigen::Vector3d gv = 0.5 * (q.w() * t + t.cross(ev));
  CVector8 z;
  z << q.w(), ev.cast<Complex>(), -0.5 * t.dot(ev), gv.cast<Complex>();
  return z;
}

void StudyToComplexPose(const CVector8& z, CMatrix3* rotation, CVector3* translation) {
  const Complex e0 = z[0], g0 = z[4];
  const CVector3 ev = z.segment<3>(1), gv = z.segment<3>(5);
  const Complex delta = e0 * e0 + Dot(ev, ev);
  CMatrix3 skew;
  skew << 0.0, -ev[2], ev[1], ev[2], 0.0, -ev[0], -ev[1], ev[0], 0.0;
  const CMatrix3 m = (e0 * e0 - Dot(ev, ev)) * CMatrix3::Identity() + 2.0 * ev * ev.transpose() + 2.0 * e0 * skew;
  *rotation = m / delta;
  // vec(g ē) = -g0 ev + e0 gv - gv × ev
  *translation = 2.0 * (-g0 * ev + e0 * gv - Cross(gv, ev)) / delta;
}

}  // namespace hexcal
