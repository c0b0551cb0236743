#include <viscofilm/biofilm/biofilm.h>
#include <viscofilm/core/input.h>
#include <viscofilm/geometry/boundary_conditions.h>

namespace viscofilm
{
  template <int dim>
  std::vector<NamedBoundaryId>
  named_boundaries(const std::string &       names,
                   const std::string &       parameter,
                   const BoundaryConditions<dim> &boundary_conditions)
  {
    std::vector<NamedBoundaryId> boundaries;
    for (const std::string &name : Utilities::split_string_list(names))
      {
        for (const auto &boundary : boundaries)
          check_input(boundary.name != name,
                      parameter + ": \"" + name + "\" is listed twice");
        boundaries.push_back({name, boundary_conditions.id(name, parameter)});
      }
    return boundaries;
  }


  template <int dim>
  void
  Biofilm<dim>::declare_entries(ParameterHandler &prm)
  {
    prm.declare_entry("Stress threshold",
                      "1",
                      Patterns::Double(0),
                      "von Mises stress of the total stress above which the "
                      "biofilm counts as prone to detach (statistics.csv: "
                      "detachment_area), in the run's stress unit: ηs U0/L0 "
                      "(≈ 0.0167 Pa with Table 4.1), Pa with Units = SI. With "
                      "Release = true also the biofilm's strength: the load of "
                      "Criterion above it releases the biofilm.");
    prm.declare_entry("Interface volume fraction",
                      "0.05",
                      Patterns::Double(0, 1),
                      "φ of the biofilm outline: the biofilm is φ >= this, its "
                      "interface the contour φ = this. In (0, 1).");
    prm.declare_entry("Walls",
                      "Bottom",
                      Patterns::List(Patterns::Anything()),
                      "The boundaries (names of Boundary conditions, "
                      "comma-separated) on which statistics.csv's "
                      "wall_shear_stress_mean/max are taken: the tangential "
                      "traction the fluid exerts on them (doc/loads.md). "
                      "Empty: none (the columns are 0). The default, Bottom "
                      "(the thesis' wall), means none on a mesh without a "
                      "boundary of that name.");
  }


  template <int dim>
  void
  Biofilm<dim>::parse_entries(ParameterHandler &             prm,
                              const BoundaryConditions<dim> &boundary_conditions)
  {
    stress_threshold = prm.get_double("Stress threshold");
    interface_level  = prm.get_double("Interface volume fraction");
    const bool has_bottom =
      std::any_of(boundary_conditions.boundaries.begin(),
                  boundary_conditions.boundaries.end(),
                  [](const typename BoundaryConditions<dim>::Boundary &b) { return b.name == "Bottom"; });
    const std::string wall_names = prm.get("Walls");
    walls = (wall_names == "Bottom" && !has_bottom) ?
              std::vector<NamedBoundaryId>() :
              named_boundaries(wall_names, "Detachment/Walls", boundary_conditions);
    check_input(interface_level > 0 && interface_level < 1,
                "Detachment/Interface volume fraction must be in (0, 1), got " +
                  to_text(interface_level));
  }


#define INSTANTIATE(dim)                                                        \
  template std::vector<NamedBoundaryId> named_boundaries(const std::string &,    \
                                                         const std::string &,    \
                                                         const BoundaryConditions<dim> &); \
  template struct Biofilm<dim>;
  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
