#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>

#include <deal.II/numerics/rtree.h>

#include <viscofilm/biofilm/growth.h>
#include <viscofilm/core/dof_cell.h>
#include <viscofilm/core/input.h>
#include <viscofilm/postprocess/output.h>
#include <viscofilm/transport/substrate.h>
#include <viscofilm/transport/volume_fraction.h>

#include <algorithm>
#include <cmath>

namespace viscofilm
{
  template <int dim>
  void
  Growth<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Growth");
    prm.declare_entry("Enable",
                      "false",
                      Patterns::Bool(),
                      "The biofilm grows on the substrate it consumes: φ "
                      "gains Y/ρX per unit of S consumed (the Monod kinetics "
                      "of subsection Substrate, which must be enabled) and "
                      "loses b φ by decay (doc/model.md, \"Growth\").");
    prm.declare_entry("Decay rate",
                      "0",
                      Patterns::Double(0),
                      "b [1/s], the biomass' decay (endogenous respiration, "
                      "lysis); its volume is lost.");
    prm.declare_entry("Maximum volume fraction",
                      "1",
                      Patterns::Double(0),
                      "φmax in (0, 1], the volume fraction of grown biofilm: "
                      "φ stays within [0, φmax].");
    prm.declare_entry("Expansion",
                      "flow",
                      Patterns::Selection("flow|none"),
                      "How new biomass makes room. flow: the mixture expands, "
                      "∇·u = P/φmax with P the net growth rate, so the flow "
                      "pushes the biofilm's surface out and φ stays below "
                      "φmax (needs a boundary of Type outflow, "
                      "traction free or pressure for the added volume to "
                      "leave). none: φ grows where it is; what would exceed "
                      "φmax goes to the biofilm's fronts.");
    prm.leave_subsection();
  }


  template <int dim>
  void
  Growth<dim>::Parameters::parse_parameters(ParameterHandler &             prm,
                                            const bool                     substrate_enabled,
                                            const BoundaryConditions<dim> &boundary_conditions)
  {
    prm.enter_subsection("Growth");
    enabled                 = prm.get_bool("Enable");
    decay_rate              = prm.get_double("Decay rate");
    maximum_volume_fraction = prm.get_double("Maximum volume fraction");
    expansion               = (prm.get("Expansion") == "flow");
    prm.leave_subsection();
    if (!enabled)
      return;
    check_input(substrate_enabled,
                "Growth/Enable = true needs Substrate/Enable = true: the biomass "
                "grows on the substrate it consumes");
    check_input(maximum_volume_fraction > 0 && maximum_volume_fraction <= 1,
                "Growth/Maximum volume fraction must be in (0, 1], got " +
                  to_text(maximum_volume_fraction));
    check_input(!expansion || boundary_conditions.fixes_pressure_level(),
                "Growth/Expansion = flow needs a boundary of Type outflow, "
                "traction free or pressure for the volume the biomass adds "
                "to leave through; none has one (use Expansion = none)");
  }


  template <int dim>
  Growth<dim>::Growth(const Parameters &    parameters,
                      const Biofilm<dim> &  biofilm,
                      const Substrate<dim> &substrate,
                      VolumeFraction<dim> & volume_fraction)
    : parameters(parameters)
    , biofilm(biofilm)
    , substrate(substrate)
    , volume_fraction(volume_fraction)
  {}


  template <int dim>
  template <typename Function>
  TrilinosWrappers::MPI::Vector
  Growth<dim>::on_phi_nodes(const TrilinosWrappers::MPI::Vector &q1, const Function &f) const
  {
    const DoFHandler<dim> &     phi_dofs = volume_fraction.dof_handler();
    const FiniteElement<dim> &  phi_fe   = phi_dofs.get_fe();
    const FiniteElement<dim> &  q1_fe    = substrate.dof_handler().get_fe();
    const TrilinosWrappers::MPI::Vector &phi = volume_fraction.solution();
    const IndexSet &            owned    = phi_dofs.locally_owned_dofs();
    TrilinosWrappers::MPI::Vector distributed(owned, phi.get_mpi_communicator());
    std::vector<types::global_dof_index> local_dofs(phi_fe.n_dofs_per_cell());
    Vector<double>                       q1_values(q1_fe.n_dofs_per_cell());
    // The Q1 shape functions at φ's support points, the same on every cell.
    FullMatrix<double> interpolation(phi_fe.n_dofs_per_cell(), q1_fe.n_dofs_per_cell());
    for (unsigned int j = 0; j < interpolation.m(); ++j)
      for (unsigned int v = 0; v < interpolation.n(); ++v)
        interpolation(j, v) = q1_fe.shape_value(v, phi_fe.get_unit_support_points()[j]);
    for (const auto &cell : phi_dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          cell_of(substrate.dof_handler(), cell)->get_dof_values(q1, q1_values);
          cell->get_dof_indices(local_dofs);
          for (unsigned int j = 0; j < local_dofs.size(); ++j)
            if (owned.is_element(local_dofs[j]))
              {
                double value = 0;
                for (unsigned int v = 0; v < q1_values.size(); ++v)
                  value += interpolation(j, v) * q1_values(v);
                distributed[local_dofs[j]] = f(phi[local_dofs[j]], value);
              }
        }
    return distributed;
  }


  template <int dim>
  TrilinosWrappers::MPI::Vector
  Growth<dim>::monod_growth() const
  {
    const auto & kinetics = substrate.kinetics();
    const double phi_max  = parameters.maximum_volume_fraction;
    return on_phi_nodes(substrate.solution(), [&](const double phi, const double s) {
      const double c = std::max(s, 0.0);
      return kinetics.maximum_growth_rate * std::clamp(phi, 0.0, phi_max) * c /
             (kinetics.half_saturation + c);
    });
  }


  template <int dim>
  TrilinosWrappers::MPI::Vector
  Growth<dim>::ghosted(const TrilinosWrappers::MPI::Vector &owned) const
  {
    // φ's own layout: owned and relevant dofs.
    TrilinosWrappers::MPI::Vector result(volume_fraction.solution());
    result = owned;
    return result;
  }


  template <int dim>
  void
  Growth<dim>::start_step()
  {
    if (!parameters.expansion)
      return;
    // (μmax φ S/(K_S + S) − b φ)/φmax from φ^n and S^n.
    TrilinosWrappers::MPI::Vector rate = monod_growth();
    const TrilinosWrappers::MPI::Vector &phi = volume_fraction.solution();
    for (const auto i : volume_fraction.dof_handler().locally_owned_dofs())
      rate[i] = (rate[i] - parameters.decay_rate *
                             std::clamp(static_cast<double>(phi[i]),
                                        0.0,
                                        parameters.maximum_volume_fraction)) /
                parameters.maximum_volume_fraction;
    expansion_rate = ghosted(rate);
    volume_fraction.set_expansion(&expansion_rate);
  }


  template <int dim>
  const TrilinosWrappers::MPI::Vector *
  Growth<dim>::expansion() const
  {
    return parameters.expansion ? &expansion_rate : nullptr;
  }


  template <int dim>
  double
  Growth<dim>::grow(const double time_step)
  {
    const double k       = time_step;
    const double b       = parameters.decay_rate;
    const double phi_max = parameters.maximum_volume_fraction;
    AssertThrow(k * b < 1,
                ExcMessage("Growth/Decay rate × the time step is " + to_text(k * b) +
                           ": it must be < 1 for φ to stay >= 0; shorten Time "
                           "stepping/Time step"));
    // The step's balance: the transport's ∫φ less what its advective form
    // gained from ∇·u (the expansion term below takes it back), plus the
    // growth the substrate paid for, less decay.
    const double transported = volume_fraction.integral();
    const double growth_rate =
      substrate.kinetics().yield / substrate.kinetics().biomass_density * substrate.consumption_rate();
    const double target = transported - k * volume_fraction.expansion_integral() +
                          k * growth_rate - k * b * transported;

    // The Monod growth at φ's nodes, with the step's S and transported φ,
    // scaled to what the substrate consumed (the two differ by S's
    // interpolation onto φ's nodes and by the undershoots the substrate
    // clips): local where φ is, and the biomass made is Y/ρX × the
    // consumption to round-off.
    const TrilinosWrappers::MPI::Vector monod = monod_growth();
    const double made = volume_fraction.integral_of(ghosted(monod));
    const double                        scale = made > 0 ? growth_rate / made : 0.0;
    TrilinosWrappers::MPI::Vector       grown(monod);
    const TrilinosWrappers::MPI::Vector &phi = volume_fraction.solution();
    for (const auto i : volume_fraction.dof_handler().locally_owned_dofs())
      {
        const double phi_i = phi[i];
        const double rate  = scale * monod[i] - b * phi_i;
        const double room  = parameters.expansion ? 1 - phi_i / phi_max : 1.0;
        grown[i]           = std::clamp(phi_i + k * rate * room, 0.0, phi_max);
      }
    TrilinosWrappers::MPI::Vector distributed(grown);
    volume_fraction.set(distributed);
    relocated = target - volume_fraction.integral();
    // Clipping at φmax and the step's mismatch of expansion and growth
    // (the Stokes problem's P is that of S^n) go to the biofilm's fronts;
    // each pass fills at most the room there is (restore_mass()).
    // Only where there is biofilm (φ >= the interface level): the water's
    // traces of φ would otherwise take their share and grow, step after
    // step, into spurious biofilm.
    const IndexSet &              owned = volume_fraction.dof_handler().locally_owned_dofs();
    TrilinosWrappers::MPI::Vector lower(owned, distributed.get_mpi_communicator());
    TrilinosWrappers::MPI::Vector upper(lower);
    const double round_off = 1e-12 * std::abs(target);
    for (unsigned int pass = 0; pass < 10; ++pass)
      {
        for (const auto i : owned)
          {
            const double phi = volume_fraction.solution()[i];
            const bool   water = phi < biofilm.interface_level;
            lower[i]           = water ? phi : 0.0;
            upper[i]           = water ? phi : phi_max;
          }
        volume_fraction.restore_mass(target, lower, upper);
        unplaced = target - volume_fraction.integral();
        if (std::abs(unplaced) <= round_off)
          break;
      }
    produced += k * growth_rate;
    decayed += k * b * transported;
    return std::abs(unplaced) <= round_off ? 0.0 : unplaced;
  }


  template <int dim>
  std::array<double, 3>
  Growth<dim>::thickness() const
  {
    const DoFHandler<dim> &dofs     = volume_fraction.dof_handler();
    const Mapping<dim> &   mapping  = volume_fraction.mapping();
    const MPI_Comm         comm     = volume_fraction.solution().get_mpi_communicator();
    // Every rank's wall faces: their centres and areas.
    std::vector<std::pair<Point<dim>, double>> faces;
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && biofilm.is_wall(face->boundary_id()))
            faces.emplace_back(face->center(true), face->measure());
    std::vector<Point<dim>> centres;
    std::vector<double>     areas;
    for (const auto &rank_faces : Utilities::MPI::all_gather(comm, faces))
      for (const auto &[centre, area] : rank_faces)
        {
          centres.push_back(centre);
          areas.push_back(area);
        }
    if (centres.empty())
      return {{0, 0, 0}};
    const auto tree = pack_rtree_of_indices(centres);

    const QGauss<dim>   quadrature(dofs.get_fe().degree + 1);
    FEValues<dim>       values(mapping, dofs.get_fe(), quadrature, update_values | update_JxW_values);
    std::vector<double> phi(quadrature.size());
    std::vector<double> column(centres.size(), 0.0); // ∫φ of each face's cells
    for (const auto &cell : dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          values.reinit(cell);
          values.get_function_values(volume_fraction.solution(), phi);
          double biomass = 0;
          for (const unsigned int q : values.quadrature_point_indices())
            biomass += phi[q] * values.JxW(q);
          std::vector<unsigned int> nearest;
          tree.query(boost::geometry::index::nearest(cell->center(true), 1),
                     std::back_inserter(nearest));
          column[nearest[0]] += biomass;
        }
    Utilities::MPI::sum(column, comm, column);
    double area = 0, mean = 0, largest = 0, deviation = 0;
    for (unsigned int f = 0; f < column.size(); ++f)
      {
        column[f] /= parameters.maximum_volume_fraction * areas[f];
        area += areas[f];
        mean += areas[f] * column[f];
        largest = std::max(largest, column[f]);
      }
    mean /= area;
    for (unsigned int f = 0; f < column.size(); ++f)
      deviation += areas[f] * std::abs(column[f] - mean);
    return {{mean, largest, mean > 0 ? deviation / (mean * area) : 0.0}};
  }


  template <int dim>
  void
  Growth<dim>::add_statistics(CsvFile &statistics, const double /*time*/) const
  {
    statistics.set("biomass_produced", produced);
    statistics.set("biomass_decayed", decayed);
    statistics.set("biomass_relocated", relocated);
    statistics.set("biomass_unplaced", unplaced);
    const auto [mean, largest, roughness] = thickness();
    statistics.set("biofilm_thickness_mean", mean);
    statistics.set("biofilm_thickness_max", largest);
    statistics.set("biofilm_thickness_roughness", roughness);
  }


  template <int dim>
  void
  Growth<dim>::save_state(CheckpointValues &values) const
  {
    values["biomass_produced"] = produced;
    values["biomass_decayed"]  = decayed;
  }


  template <int dim>
  void
  Growth<dim>::load_state(const CheckpointValues &values)
  {
    produced = checkpoint_value(values, "biomass_produced");
    decayed  = checkpoint_value(values, "biomass_decayed");
  }


  VISCOFILM_INSTANTIATE(Growth)
} // namespace viscofilm
