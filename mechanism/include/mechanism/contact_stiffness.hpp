#pragma once
// Contact stiffness K of the normal laws in contact_law.hpp, from material and geometry only.
//
//  - material_compliance: sigma = (1 - nu^2) / E, the seed's Eq. (13) (m^2/N).
//  - journal_bearing_stiffness: Hertz line-contact reading used by Flores for a journal of radius
//    R_j in a bearing of radius R_b (internal contact, curvatures of opposite sign):
//        K = (4/3) / (sigma_b + sigma_j) * sqrt(R_b R_j / (R_b - R_j))        (N/m^1.5)
//    About 6.6e10 at c = 0.5 mm and 4.8e11 at c = 0.01 mm for steel (E = 207 GPa, nu = 0.3,
//    R_b = 10 mm): K grows without bound as the clearance R_b - R_j -> 0.
//  - contact_length: the seed's Eq. (12), the length of one slider face inside the guide surface
//    from the penetrations of its two corners (the face is straight, so the penetration varies
//    linearly between them).
//  - slider_face_stiffness: the seed's Eq. (11) (Wu et al.)
//        K = sqrt(S) / (sigma_i + sigma_j) / (11.15 (L_s/L_c + 15.72)^-1 + 0.2854),  S = L_c W.
//    The seed calls S "the area of the contact region" without defining it; S = L_c x W (contact
//    length times slider width) is our reading. Note the formula gives N/m (a linear stiffness),
//    which the seed then uses in K delta^1.5. K is 0 at L_c = 0 and increases with L_c on
//    (0, L_s] (the denominator grows with L_c, but slower than sqrt(L_c): see the docs).
// All arguments are parameters, not state: anything outside its domain (including NaN) throws
// InvalidParameter naming it.

namespace mechanism {

// sigma = (1 - nu^2) / E; requires E > 0 (finite, Pa) and 0 <= nu < 0.5.
double material_compliance(double young_modulus, double poisson_ratio);

// Hertz stiffness of a journal in a bearing (Flores): requires sigma_bearing, sigma_journal > 0
// and R_b > R_j > 0 (m).
double journal_bearing_stiffness(double sigma_bearing, double sigma_journal, double bearing_radius,
                                 double journal_radius);

// Seed Eq. (12): L_s if both penetrations are > 0, 0 if both are <= 0, else
// L_s max(dA, dB) / |dA - dB| (which lies in (0, L_s]). Requires L_s > 0 (finite); a NaN
// penetration gives NaN (it is state, not a parameter).
double contact_length(double slider_length, double penetration_a, double penetration_b);

// Seed Eq. (11) with S = L_c W; 0 when L_c = 0. Requires sigmas > 0, L_s > 0, W > 0 and
// 0 <= L_c <= L_s (contact_length never returns more than L_s).
double slider_face_stiffness(double sigma_slider, double sigma_guide, double slider_length,
                             double slider_width, double contact_length);

}  // namespace mechanism
