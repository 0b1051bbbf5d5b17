#pragma once
// Closed forms of rod buckling, for the "literature" family (docs/validation.md, where each is
// derived; the Cosserat corrections are derived there, not taken from the thesis).
//
// Post-buckled clamped-free elastica (inextensible; Timoshenko & Gere, Theory of Elastic
// Stability, 2nd ed., 1961, section 2.7): a compressive dead tip load P buckles the column to the
// tip angle alpha with k = sin(alpha / 2),
//     P L^2 / EI = K(k)^2,   x_tip / L = 2 k / K(k),   z_tip / L = 2 E(k) / K(k) - 1.
//
// Euler's loads of a Cosserat column (linear law (2.28), shear GA, extension EA). Linearising the
// planar balance EI theta'' + p'_x P = 0 about the straight compressed rod, whose strains are
// nu1 = P sin theta / GA and nu3 = 1 - P cos theta / EA, gives
//     EI theta'' + P (1 + P/GA - P/EA) theta = 0,
// so the critical load solves P (1 + P/GA - P/EA) = P_E, with P_E = pi^2 EI / (beta L)^2 and
// beta = 2 (clamped-free), 1 (pinned-pinned), 1/2 (clamped-clamped): the shear term is Haringx's
// and lowers P, the shortening raises it. Kirchhoff: P = P_E.
//
// Greenhill's clamped-clamped shaft under an end twisting moment M (Greenhill 1883; Timoshenko &
// Gere section 2.18). The lateral tilt t = t_x + i t_y of the sections obeys
// EI i t'' + M t' = -i N (N the lateral end reaction) and the centreline w' = t + N / GA; the
// clamped ends t(0) = t(L) = w(0) = w(L) = 0 have a non-zero solution when, with
// mu = M L / EI and g = EI / (GA L^2),
//     tan(mu / 2) = mu / (2 (1 + g mu^2)),
// the classic tan(mu/2) = mu/2, mu = 8.9868, for an unshearable rod (g = 0).
//
// Greenhill's pinned shaft (both ends on ball joints, the twisting moment M fixed along the
// axis; Greenhill 1883, Timoshenko & Gere 2.18): the lateral displacement w = w_x + i w_y obeys
// B w'' - i M w' = -N s + D with the end conditions w = 0 and B w'' - i M w' = 0 (the end moment
// stays axial), so N = D = 0 and w = c0 + c2 exp(i M s / B): w(0) = w(L) = 0 has a non-zero
// solution first at M L / B = 2 pi. Its mode carries no force at all, so the rod is under the
// moment M e_z alone, for which the tangent precesses exactly, t' = (M / B) e_z x t (isotropic
// bending: t x m = -B t'; shear and extension carry nothing): a rod tilted by theta0 at one end
// and loaded only by M e_z at the other is a helix whose far end returns to the axis through the
// first exactly at M L / B = 2 pi, for any theta0 and for Kirchhoff and Cosserat rods alike.
// rodlab's base is always clamped, which here is the pin (the clamp carries no lateral moment:
// the internal moment is M e_z everywhere), so the check measures that closing moment.
//
// Lateral-torsional buckling of a cantilever strip (Prandtl 1899, Michell 1899; Timoshenko &
// Gere section 6.3) under a tip force P through the centroid in its stiff plane, the strip rigid
// in that plane: the twist phi obeys GJ phi'' + P^2 (L - s)^2 / (EI_weak) phi = 0 with phi(0) = 0
// and phi'(L) = 0, whose solution sqrt(L - s) J_{-1/4}(gamma (L - s)^2 / (2 L^2)) gives
//     P_cr = gamma sqrt(EI_weak GJ) / L^2,   gamma the first root of J_{-1/4}(gamma / 2) = 0,
// gamma = 4.0126. A finite in-plane stiffness raises it by a relative O(EI_weak / EI_strong).

namespace rodlab::validation::reference {

struct PostBuckledElastica {
  double load = 0.0;  ///< P L^2 / EI
  double x = 0.0;     ///< tip lateral deflection / L
  double z = 0.0;     ///< tip axial position / L
};

/// The post-buckled clamped-free elastica at tip angle alpha in (0, pi).
PostBuckledElastica post_buckled_elastica(double alpha);

/// The critical compressive load of a Cosserat column with Euler load P_E (Kirchhoff: GA = EA =
/// 0, the load P_E itself).
double cosserat_critical_load(double euler_load, double GA, double EA);

/// Greenhill's critical twisting moment of a clamped-clamped rod, M L / EI, for the shear
/// parameter g = EI / (GA L^2) (0: unshearable).
double greenhill_clamped_moment(double g);

/// The lateral-torsional buckling constant gamma = 4.0126 of the cantilever strip.
double lateral_torsional_constant();

}  // namespace rodlab::validation::reference
