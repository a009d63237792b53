// The forward-kinematics equations of a general 6-6 platform in Study
// parameters, the polynomial system that fk_homotopy.cc solves for every
// assembly mode.
//
// A pose (R, t) is written with a rotation quaternion e = (e0, ev) and a dual
// quaternion part g = (g0, gv), both unnormalised (Study 1891, Husty 1996):
//   R = M(e) / Δ,  Δ = e·e,  M(e) = (e0² - ev·ev) I + 2 ev evᵀ + 2 e0 [ev]x
//   t = 2 vec(g ē) / Δ,      g = ½ (0, t) ⊗ e
// The 8 unknowns z = (e0, ev, g0, gv) satisfy 8 polynomial equations:
//   f_i (i = 0..5)  Δ·(|R b_i + t - a_i|² - d_i²) = 0, a quadric in z:
//       D Δ + 4 g·g - 4 g0 (b·ev) + 4 e0 (b·gv) - 4 b·(ev × gv)
//       - 2 tr(Aᵀ M(e)) + 4 g0 (a·ev) - 4 e0 (a·gv) + 4 a·(gv × ev)
//     with D = a·a + b·b - d², A = a bᵀ;
//   f_6  the Study quadric e0 g0 + ev·gv = 0 (t is a pure vector);
//   f_7  h·z - 1 = 0, a random complex chart that fixes the projective scale.
// A general platform has 40 isolated complex solutions with Δ ≠ 0 (Husty
// 1996; Wampler 1996); solutions with Δ = 0 are spurious (the exceptional
// quadric) and dropped.
//
// Every product is the plain (bilinear) one: no complex conjugation, so the
// equations are holomorphic and homotopy continuation applies.
#pragma once

#include <Eigen/Core>
#include <array>
#include <complex>

#include "core/pose.h"

namespace hexcal {

using Complex = std::complex<double>;
using CVector3 = Eigen::Matrix<Complex, 3, 1>;
using CVector8 = Eigen::Matrix<Complex, 8, 1>;
using CMatrix8 = Eigen::Matrix<Complex, 8, 8>;
using CMatrix3 = Eigen::Matrix<Complex, 3, 3>;

constexpr int kStudyUnknowns = 8;

// The geometry of one problem instance: attachment points and squared leg lengths.
struct StudyParameters {
  std::array<CVector3, 6> a;  // base points
  std::array<CVector3, 6> b;  // platform points
  std::array<Complex, 6> d2;  // squared total leg lengths (L_i + l_i)²
};

// Each leg equation is linear in these coefficients (plus the fixed 4 g·g).
struct LegCoefficients {
  Complex d;  // D = a·a + b·b - d²
  CVector3 a, b;
  CMatrix3 ab;  // A = a bᵀ
};

LegCoefficients CoefficientsOf(const CVector3& a, const CVector3& b, const Complex& d2);
// d(coefficients)/ds along p(s) = p + s·dp.
LegCoefficients CoefficientDerivative(const CVector3& a, const CVector3& b, const CVector3& da, const CVector3& db,
                                      const Complex& dd2);

// Value and gradient (w.r.t. z) of the part of a leg equation that is linear in
// the coefficients (everything but 4 g·g).
Complex LegLinearPart(const LegCoefficients& c, const CVector8& z, CVector3* unused = nullptr);
void LegLinearPartGradient(const LegCoefficients& c, const CVector8& z, Eigen::Matrix<Complex, 1, 8>* grad);

// F(z) and dF/dz for the 8 equations above; either may be null when not needed.
void EvaluateStudySystem(const std::array<LegCoefficients, 6>& legs, const CVector8& chart, const CVector8& z,
                         CVector8* f, CMatrix8* jacobian);

// Study parameters of a real pose (e normalised, e0 >= 0) and back. PoseFromStudy
// takes real parts; call it only for solutions whose imaginary part is negligible.
CVector8 StudyFromPose(const Pose& pose);
// Complex rotation M(e)/Δ and translation 2 vec(g ē)/Δ of a solution.
void StudyToComplexPose(const CVector8& z, CMatrix3* rotation, CVector3* translation);

}  // namespace hexcal
