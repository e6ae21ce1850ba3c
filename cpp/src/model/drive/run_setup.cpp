// What every run of a drive starts from (run_setup.hpp).
#include "run_setup.hpp"

#include <array>
#include <memory>
#include <vector>

#include "leadscrew/core/errors.hpp"
#include "leadscrew/model/drive_equilibrium.hpp"

namespace leadscrew::model::drive {

const friction::Law& running_law(const DriveModel& model, const std::string& integrator,
                                 std::unique_ptr<friction::Law>& regularization) {
  const bool ode_alone = integrator != "event_driven" && integrator != "moreau";
  regularization.reset();
  if (ode_alone && model.law().resolution() == friction::Resolution::set_valued) {
    regularization = model.law().regularized();
    if (!regularization)
      throw InvalidArgument("integrator = \"" + integrator + "\" is invalid with friction.law = \"" +
                            model.parameters().friction +
                            "\": the law has no regularization for an ODE method");
  }
  return regularization ? *regularization : model.law();
}

StateLayout state_layout(const DriveModel& model, const friction::Law& law) {
  return StateLayout(model, law);
}

Eigen::VectorXd initial_vector(const DriveModel& model, const StateLayout& layout) {
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(layout.size());
  const DriveStart start = initial_state(model);  // initial.state: relaxed or in equilibrium
  layout.compress(start.q, start.v, y0.data());
  initial_element_states(model, layout, start.q.data(), start.v.data(),
                         model.parameters().initial_state == InitialState::equilibrium,
                         y0.data());
  return y0;
}

void initial_element_states(const DriveModel& model, const StateLayout& layout, const double* q,
                            const double* v, bool at_equilibrium, double* y) {
  const std::vector<std::shared_ptr<const Element>>& elements = model.elements().elements;
  const std::vector<std::pair<int, int>> slots = layout.element_slots();
  // (an element sees its own states as zeros: it is asked for them)
  const std::array<double, kMaxElementStates> zeros{};
  for (std::size_t k = 0; k < elements.size(); ++k) {
    if (slots[k].first < 0 || slots[k].second == 0) continue;
    const ElementState s{0.0, q, v, zeros.data()};
    elements[k]->initial_states(s, at_equilibrium, y + slots[k].first);
  }
}

}  // namespace leadscrew::model::drive
