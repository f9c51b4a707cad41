#include "wire_table.h"
#include "text_format.h"

#include <cstdio>
#include <ostream>
#include <string>

namespace wirerig::cli {

void PrintWireTable(std::ostream& out, const WireProblem& problem, const WireSolution& solution) {
  const Material& m = problem.material;
  out << Format("wire: L = %g m, E = %g Pa, nu = %g, A = %g m^2, I = %g m^4\n", problem.length,
                m.youngs_modulus, m.poisson_ratio, problem.section.area,
                problem.section.second_moment);
  out << Format("stiffness: EA = %g N, EI = %g N m^2\n", solution.stiffness.axial,
                solution.stiffness.bending);
  if (problem.bending)
    out << "bending: " << ToString(problem.bending->boundary) << ", "
        << ToString(problem.bending->mode) << " solution\n";
  if (problem.axial) out << Format("axial: fixed at v0 = %g\n", problem.axial->fixed_at);
  out << "\n";

  const bool bending = !solution.bending.empty(), axial = !solution.axial.empty();
  out << "     v      s [m]";
  if (bending) out << "     X_x [mm]     X_y [mm]     X_z [mm]  slope [rad]   M [N m]";
  if (axial) out << "   axial [mm]      N [N]";
  out << "\n";
  for (std::size_t i = 0; i < solution.v.size(); ++i) {
    out << Format("%6.3f %10.4f", solution.v[i], solution.v[i] * problem.length);
    if (bending) {
      const Vec3 x = solution.bending[i] * 1e3;
      const double moment = solution.stiffness.bending * solution.curvature[i].norm();
      out << Format(" %12.5f %12.5f %12.5f %12.6f %9.4f", x.x(), x.y(), x.z(),
                    solution.slope[i].norm(), moment);
    }
    if (axial) out << Format(" %12.6f %10.4f", solution.axial[i] * 1e3, solution.normal_force[i]);
    out << "\n";
  }
}

}  // namespace wirerig::cli
