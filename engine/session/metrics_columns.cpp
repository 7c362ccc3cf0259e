// The metrics CSV's columns (simulation.h): one row per frame, the FrameMetrics fields by name.
#include <iomanip>
#include <sstream>
#include <type_traits>
#include <variant>

#include "engine/session/simulation.h"

namespace galsculpt {

const std::vector<MetricsColumn>& metricsColumns() {
  using M = FrameMetrics;
  static const std::vector<MetricsColumn> columns = {
      {"frame", &M::frame},
      {"time_s", &M::timeS},
      {"ms_total", &M::msTotal},
      {"ms_elements", &M::msElements},
      {"ms_solve", &M::msSolve},
      {"ms_plastic", &M::msPlastic},
      {"ms_other", &M::msOther},
      {"volume", &M::volume},
      {"volume_change_pct", &M::volumeChangePct},
      {"kinetic_energy", &M::kineticEnergy},
      {"elastic_energy", &M::elasticEnergy},
      {"residual", &M::residual},
      {"max_displacement", &M::maxDisplacement},
      {"damaged_edges", &M::damagedEdges},
      {"pieces", &M::pieces},
      {"warnings", &M::warnings},
      {"newton_iterations", &M::newtonIterations},
      {"contact_force_n", &M::contactForceN},
      {"ms_fracture", &M::msFracture},
      {"opening_m", &M::openingM},
      {"load_n", &M::loadN},
      {"backtracks", &M::backtracks},
      {"cg_iterations", &M::cgIterations},
      {"converged", &M::converged},
      {"energy_passes", &M::energyPasses},
      {"debris_pieces", &M::debrisPieces},
      {"debris_volume_pct", &M::debrisVolumePct},
      {"inverted_pieces", &M::invertedPieces},
      {"striker_displacement_m", &M::strikerDisplacementM},
      {"absorbed_energy_j", &M::absorbedEnergyJ},
      {"debris_mass_kg", &M::debrisMassKg},
      {"piece_residual", &M::pieceResidual},
      {"local_iterations", &M::localIterations},
      {"idle_tools", &M::idleTools},
      {"launches", &M::launches},
      {"syncs", &M::syncs},
      {"graphs", &M::graphs},
      {"h2d_bytes", &M::hostToDeviceBytes},
      {"d2h_bytes", &M::deviceToHostBytes},
      {"barriers", &M::barriers},
  };
  return columns;
}

std::string metricsCsvHeader() {
  std::string header;
  for (const MetricsColumn& c : metricsColumns())
    header.append(header.empty() ? "" : ",").append(c.name);
  return header;
}

std::string metricsCsvRow(const FrameMetrics& m) {
  std::ostringstream s;
  s << std::setprecision(9);
  bool first = true;
  for (const MetricsColumn& c : metricsColumns()) {
    if (!first) s << ',';
    first = false;
    std::visit(
        [&](auto field) {
          if constexpr (std::is_same_v<std::decay_t<decltype(m.*field)>, bool>)
            s << (m.*field ? 1 : 0);
          else
            s << m.*field;
        },
        c.field);
  }
  return s.str();
}

}  // namespace galsculpt
