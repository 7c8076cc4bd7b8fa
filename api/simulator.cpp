#include "api/simulator.h"

#include "runtime/simulation/simulate.h"
#include "runtime/simulation/simulator.h"

namespace mbfe {

namespace {

/// The request checked against the model file before the model is assembled.
const Model& checked(const Model& model, const runtime::SimulationRequest& request) {
  runtime::check_request_early(model.ir(), request);
  return model;
}

}  // namespace

Simulator::Simulator(const Model& model, const runtime::SimulationRequest& request)
    : model_(checked(model, request)),
      sim_(std::make_unique<runtime::Simulator>(model_.assembled_for(request.adjust), request)) {}
Simulator::~Simulator() = default;
Simulator::Simulator(Simulator&&) noexcept = default;
Simulator& Simulator::operator=(Simulator&&) noexcept = default;

const runtime::OutputLayout& Simulator::layout() const { return sim_->layout(); }

int Simulator::column(const std::string& name) const {
  const std::vector<std::string>& columns = sim_->layout().columns;
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (columns[k] == name) return static_cast<int>(k);
  std::string all;
  for (const std::string& c : columns) all += (all.empty() ? "" : ", ") + c;
  throw runtime::InvalidInput("no output column '" + name + "' (the columns: " + all + ")");
}

const std::vector<std::string>& Simulator::notices() const { return sim_->notices(); }
const std::string& Simulator::variant() const { return sim_->variant(); }
double Simulator::time() const { return sim_->time(); }
double Simulator::step() const { return sim_->step(); }
double Simulator::t_end() const { return sim_->t_end(); }
std::int64_t Simulator::steps() const { return sim_->steps(); }
std::int64_t Simulator::total_steps() const { return sim_->total_steps(); }
bool Simulator::finished() const { return sim_->finished(); }
runtime::SimulationStatus Simulator::status() const { return sim_->status(); }

runtime::SimulationStatus Simulator::advance_to(double t, const runtime::StepMonitor& keep_going) {
  return sim_->advance_to(t, keep_going);
}
runtime::SimulationStatus Simulator::advance_steps(std::int64_t n, const runtime::StepMonitor& keep_going) {
  return sim_->advance_steps(n, keep_going);
}
void Simulator::state(Eigen::VectorXd& q, Eigen::VectorXd& qd) { sim_->state(q, qd); }
void Simulator::set_state(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) { sim_->set_state(q, qd); }
const std::vector<double>& Simulator::outputs() { return sim_->outputs(); }
runtime::OutputRow Simulator::row() { return sim_->row(); }
void Simulator::set_beam_load(const std::string& beam, double s, std::function<double(double)> value) {
  sim_->set_beam_load(beam, s, std::move(value));
}
runtime::SimulationReport Simulator::report() { return sim_->report(); }
void Simulator::note_row_fault(const std::string& fault) { sim_->note_row_fault(fault); }

}  // namespace mbfe
