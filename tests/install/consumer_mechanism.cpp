// Links against the installed simulator and checks one fact of its scene handling and one of its
// physics: the built-in seed scene integrates the conrod and slider angles (seed Eq. 27), and with
// every joint ideal the slider sits at x = crank + conrod at crank angle 0.
#include <mechanism/scene.hpp>
#include <mechanism/simulate.hpp>

#include <cmath>

int main() {
  const mechanism::SliderCrank seed(mechanism::read_scene(""));
  if (seed.coordinate_count() != 2) return 1;
  mechanism::SliderCrank ideal(mechanism::read_scene("", {"joint.slider.type=ideal", "run.duration=0.001"}));
  mechanism::Evaluation ev;
  ideal.evaluate(0.0, ideal.initial_state(), ev);
  if (std::abs(ev.slider_pose[0] - 0.17) > 1e-12) return 2;
  return mechanism::simulate(ideal).status == mechanism::SimulationStatus::completed ? 0 : 3;
}
