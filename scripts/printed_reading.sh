# Sourced by the measurement scripts. The seed's slider joint as printed: the face resultant of
# Eq. 18-19, Eq. 11 with exponent 1.5, the absolute LuGre with a constant sigma1. It was the built-in
# scene's reading until the audited one replaced it (docs/reference/mechanism/scene.md). The tables
# those scripts wrote were measured on it, so their scenes start from it: a rerun reproduces the
# table it documents, and a variant's own --set arguments still come after and win.
printed_reading="--set joint.slider.model=face --set joint.slider.contact.exponent=1.5 \
--set joint.slider.friction.law=lugre_absolute --set joint.slider.friction.sigma1_velocity=0"
