// Internal to the runtime: checks and projections shared by the modal wire jobs
// (modal_wire.cpp, modal_wire_evaluate.cpp). None allocates.
#pragma once

#include <span>

#include "wirerig/runtime/modal_wire.h"

namespace wirerig::detail {

// Checks the loads for the model's family, length and stiffness (BendingJob's rules and field
// names) and the support's motion. The model must be valid.
Status ValidateModalLoads(const ModalWireModel& model, const ModalWireLoads& loads);
// The support's motion alone (acceleration, angular velocity, angular acceleration): finite,
// and their inertial loads bounded like BendingJob's.
Status ValidateSupportMotion(const ModalWireModel& model, const ModalWireLoads& loads);

// Checks that the state belongs to the model (mode count) and holds finite, bounded values.
Status ValidateModalState(const ModalWireModel& model, const ModalWireState* state);

// q_n_static of valid loads for every mode of a valid model; out holds basis.modes elements.
// point_load_modes: empty, or phi_n(at_j) at [j * modes + n] (TabulateModes of the positions).
void StaticModalCoordinates(const ModalWireModel& model, const ModalWireLoads& loads,
                            std::span<const double> point_load_modes, std::span<Vec3> out);

// sqrt(EI / (rho A L^4)), rad/s, of a valid model.
double NaturalFrequency(const ModalWireModel& model);

}  // namespace wirerig::detail
