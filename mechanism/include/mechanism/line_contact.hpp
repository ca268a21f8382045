#pragma once
// A straight slider face pressed into a flat guide surface as a line contact: every point s of the
// face that penetrates, by d(s) > 0, carries a normal pressure (K / L) d(s)^n, where L is the
// face's length and K the stiffness of the whole face (a face penetrating uniformly by d feels
// K d^n, as in the seed's Eq. 10 with the flat-face stiffness of Eq. 11). The face is straight, so
// d runs linearly from the left corner's penetration a to the right corner's b:
//     d(t) = a + (b - a) t,   t = s / L in [0, 1].
// The elastic part is the gradient of the potential
//     U(a, b) = K  integral_0^1 d(t)_+^(n+1) / (n+1) dt,
// and the pressure is statically equivalent to two normal forces at the corners,
//     F_a = dU/da = K integral (1 - t) d_+^n dt,   F_b = dU/db = K integral t d_+^n dt
// (the linear shape functions of the face). Applied at the corners, along the guide's normal, they
// are exact generalised forces of U: with no damping and no friction the contact stores and
// returns energy whatever the slider's tilt. The seed's Eq. 18-19 (one force sized by the deepest
// corner, at the centroid of the penetrated region) is not a gradient and creates energy once the
// slider tilts (docs/reference/mechanism/model.md, "Energy from a tilted start").
//
// The integrals are evaluated in closed form: for one penetrating corner over the penetrated part;
// for two, about the face's mean penetration, with a series where the two are nearly equal (the
// closed form would cancel), so the loads are accurate to a few ulp for any a and b.

namespace mechanism {

struct LineContactLoads {
  double left = 0.0;   // F_a, N: at the face's left corner (penetration a)
  double right = 0.0;  // F_b, N: at the right corner (penetration b)
};

// The corner loads of the elastic pressure. Both 0 when neither corner penetrates. Throws
// InvalidParameter for a stiffness that is negative or not finite ("stiffness") or an exponent that
// is not finite and > 0 ("exponent"); NaN penetrations (state) propagate to the result.
LineContactLoads line_contact_loads(double stiffness, double exponent, double penetration_a, double penetration_b);

// The potential U(a, b) above (J): the elastic energy stored in the face's contact.
double line_contact_energy(double stiffness, double exponent, double penetration_a, double penetration_b);

}  // namespace mechanism
