#pragma once
// A cell type: everything the cells of one kind share (dissertation Secs. 2.2-2.4).
// - a reference shape (shapes.hpp) sampled at n_d data sites: the reference configuration;
// - surface operators from the data sites to n_s sample sites (RBF, eqs. 2.15-2.19, or factored
//   spherical harmonics, paper eqs. 85-86), built once on the host and uploaded; with bending the
//   same operator set also evaluates at the n_d data sites (rows n_s .. n_s + n_d - 1), so that
//   one product gives the jets at both (bending needs H at the data sites);
// - reference jets Z at the sample sites, from the same operators applied to the reference data
//   (so that a rigid motion of the reference carries no elastic force beyond rounding);
// - reference area weights dA0 (eq. 51 with the sphere weights of eq. 2.22, phi = r, unless
//   given), in cm^2;
// - a force model: a list of energies of Sec. 2.2 with CGS parameters.
// A type is immutable after construction and shared (std::shared_ptr) by the batches of it.
#include "rbfib/linalg/dense.hpp"
#include "rbfib/cells/shapes.hpp"
#include "rbfib/mechanics/energy.hpp"
#include "rbfib/surface/geometry_kernels.hpp"
#include "rbfib/surface/operators.hpp"

#include <memory>
#include <string>
#include <vector>

namespace rbfib::cells {

/// The energies acting on a cell of a type (dissertation Sec. 2.2), CGS units.
struct ForceModel {
  /// Elastic energy densities W(I1, I2), summed: Skalak (2.11), neo-Hookean (2.12 or paper 68),
  /// surface tension (paper 72). At most max_elastic_energies.
  std::vector<mechanics::EnergyDensity> elastic;
  /// Canham-Helfrich bending (2.13), W = 2 kappa (H - H')^2; kappa in erg, 0 for none.
  double kappa = 0;
  /// Constant spontaneous curvature H' (1/cm), unless H0_reference.
  double H0 = 0;
  /// H' = the mean curvature of the reference shape, a material field (the platelet's
  /// "preference for its reference curvature", Sec. 2.2).
  bool H0_reference = false;
  /// Membrane viscosity nu of the dissipation (2.14), dyn s/cm; 0 for none.
  double nu = 0;

  static constexpr int max_elastic_energies = 4;
  bool bending() const { return kappa > 0; }
  bool dissipation() const { return nu > 0; }
  /// One line listing the energies and their parameters with units.
  std::string describe() const;
};

enum class Interpolant { rbf, spherical_harmonics };

struct CellTypeSpec {
  std::string name;
  ReferenceShape shape;
  surface::SphereSites data_sites, sample_sites;
  Interpolant interpolant = Interpolant::rbf;
  surface::PhsBasis basis;  ///< RBF: phi = r^power, harmonics of degree <= sh_degree
  int sh_degree = -1;       ///< spherical harmonics: degree M, data sites must number (M+1)^2
  /// Quadrature weights on S^2 at the sample sites (sum 4 pi); empty: eq. (2.22) with phi = r.
  std::vector<double> sphere_weights;
  ForceModel model;
  /// The force call's products in single precision (surface/operators.hpp, in_single_precision):
  /// faster, with errors of float rounding in the jets; off by default (studies/bench_precision).
  bool single_precision_products = false;
};

/// Flops of the dense products of one force call for N cells of a type, as performed: the jets
/// of positions at the sample sites and, with dissipation, the five derivatives of the velocities
/// there (2 x 6 n_s n_d x 3N [+ 2 x 5 n_s n_d x 3N]); with bending, the five derivatives of the
/// positions at the data sites (2 x 5 n_d n_d x 3N) and of H - H' at the sample sites, in the same
/// pass (2 x 5 n_s n_d x N): the values nothing reads are not computed; and the operator bytes
/// they stream (each operator row is read once).
struct ProductFlops {
  double jets = 0, bending = 0;
  double bytes = 0;
  double total() const { return jets + bending; }
};
ProductFlops product_flops(const CellTypeSpec& spec, index_t N);

class CellType {
 public:
  /// Builds operators, reference jets and weights. Throws InputError naming the field for bad
  /// specifications, NumericalError for singular operators or a degenerate reference.
  explicit CellType(CellTypeSpec spec);

  const std::string& name() const { return spec_.name; }
  const CellTypeSpec& spec() const { return spec_; }
  const ForceModel& model() const { return spec_.model; }
  index_t n_data() const { return spec_.data_sites.size(); }
  index_t n_sample() const { return spec_.sample_sites.size(); }

  /// The type's operators: the sample sites, then (with bending) the data sites.
  const surface::SurfaceOperators& operators() const { return *operators_; }
  /// Data -> sample and data -> data operators as sets of their own, for the per-cell host path
  /// (mechanics/shell.hpp); copies of row blocks of operators(), made on first use. at_data() is
  /// null without bending.
  const surface::SurfaceOperators& to_sample() const;
  const surface::SurfaceOperators* at_data() const;

  /// Reference positions at the data sites, n_d x 3 (device and host).
  const linalg::DeviceMatrix& reference_data() const { return reference_data_; }
  const std::vector<double>& reference_data_host() const { return reference_host_; }
  /// Reference jets Z at the sample sites (one cell, device memory).
  surface::JetView reference_jets() const;
  /// The same jets on the host (tests, per-cell reference path).
  std::vector<surface::Jet> reference_jets_host() const;
  /// Reference area weights dA0 at the sample sites (cm^2).
  const dvec& dA0() const { return dA0_; }
  std::vector<double> dA0_host() const;
  /// Material H' at the data sites (1/cm) and its scalar jets at the sample sites; empty
  /// unless model().H0_reference.
  const dvec& H0_data() const { return H0_data_; }
  surface::JetView H0_jets() const;

  double reference_area() const { return area0_; }      ///< cm^2, sum of dA0
  double reference_volume() const { return volume0_; }  ///< cm^3, (1/3) sum X . n dA0
  /// Device bytes held by this type (operators, reference data and jets, weights).
  std::size_t bytes() const;
  /// Several lines: shape, sites, interpolant, force model, memory.
  std::string describe() const;

 private:
  CellTypeSpec spec_;
  std::shared_ptr<const surface::SurfaceOperators> operators_;
  mutable std::shared_ptr<const surface::SurfaceOperators> to_sample_, at_data_;  // made on first use
  linalg::DeviceMatrix reference_data_, Z_value_, Z_derivatives_, H0_value_, H0_derivatives_;
  std::vector<double> reference_host_;
  dvec dA0_, H0_data_;
  double area0_ = 0, volume0_ = 0;
};

}  // namespace rbfib::cells
