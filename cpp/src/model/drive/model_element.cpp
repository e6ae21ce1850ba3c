// The event-driven driver's element (driver_element.hpp) for an element of
// the model behind the element interface (model/element.hpp): it forwards
// each call to the element with the element's state and mode as the
// dynamics hold them (DriveDynamics::element_state, element_mode), so the
// driver never names the element.
#include <string>

#include "driver_element.hpp"

namespace leadscrew::model::drive {

namespace {

class ModelElement final : public DriveHybrid::Element {
 public:
  ModelElement(DriveHybrid& hybrid, const model::Element& element, std::size_t index)
      : DriveHybrid::Element(hybrid), element_(element), index_(index) {}

  int root_count() const override { return element_.root_count(); }
  void roots(double t, double* g) const override {
    (void)t;
    element_.roots(state(), mode(), g);
  }
  void root_directions(int* directions) const override { element_.root_directions(directions); }
  // Its own states are y's (writable); y is expanded anew after it.
  Event handle(double t, double* y, const int* root_info) override {
    (void)root_info;
    set(t, y);
    ElementState s = state();
    s.own = y + first_state();
    const ElementEvent event = element_.handle(s, mode(), y + first_state());
    set(t, y);
    return {event.kind, event.decide_mode};
  }
  void after_mode_change(double t, const double* y) override {
    set(t, y);
    element_.after_mode_change(state(), mode());
  }
  void start(double t, const double* y) override {
    set(t, y);
    element_.start(state(), mode());
  }
  void rates(double t, const double* y, double* ydot, double* energy) const override {
    (void)t;
    (void)y;
    element_.rates(state(), mode(), ydot + first_state(), energy);
  }
  void output(double t, const double* y, const ContactForces& forces,
              ChannelState& channels) const override {
    (void)t;
    (void)y;
    (void)forces;
    if (first_channel() < 0) return;  // (it declared none)
    element_.output(state(), mode(), channels.values.data() + first_channel());
  }
  bool forces_from_loads_alone() const override { return element_.forces_from_loads_alone(); }

 private:
  ElementState state() const { return dynamics().element_state(index_); }
  ElementMode& mode() const { return dynamics_mode(index_); }

  const model::Element& element_;
  std::size_t index_;
};

}  // namespace

std::unique_ptr<DriveHybrid::Element> make_model_element(DriveHybrid& hybrid,
                                                         const DriveModel& model,
                                                         const char* name) {
  const std::vector<std::shared_ptr<const model::Element>>& elements = model.elements().elements;
  for (std::size_t k = 0; k < elements.size(); ++k)
    if (std::string(elements[k]->name()) == name)
      return std::make_unique<ModelElement>(hybrid, *elements[k], k);
  return nullptr;
}

std::unique_ptr<DriveHybrid::Element> make_model_element(DriveHybrid& hybrid,
                                                         const DriveModel& model,
                                                         std::size_t index) {
  return std::make_unique<ModelElement>(hybrid, *model.elements().elements.at(index), index);
}

}  // namespace leadscrew::model::drive
