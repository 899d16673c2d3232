// The subsurface libraries behind the renderer: radial diffusion profiles, the
// brute-force half-space simulator, Chandrasekhar's H-function albedo and the
// albedo inversion (METHODS.md sections 0, 1 and 4).
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "dermis/sss/halfspace/chandrasekhar.h"
#include "dermis/sss/halfspace/halfspace.h"
#include "dermis/sss/profiles/profile.h"
#include "dermis/sss/walk/albedo_inversion.h"
#include "interruptible.h"

namespace py = pybind11;

namespace dermis::python {

namespace {

using sss::RadialProfile;

// f applied to every element of x (a number or an array of any shape): the same shape
// back, a float for a number. (pybind11 2.10's py::vectorize cannot bind const methods.)
template <class F>
py::object map_array(const py::array_t<double, py::array::c_style | py::array::forcecast>& x, F f) {
  py::array_t<double> out(std::vector<py::ssize_t>(x.shape(), x.shape() + x.ndim()));
  const double* in = x.data();
  double* o = out.mutable_data();
  for (py::ssize_t i = 0; i < x.size(); ++i) o[i] = f(in[i]);
  if (x.ndim() == 0) return py::float_(o[0]);
  return out;
}
using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

// One channel of an RGB builder fed the same value in every channel.
RadialProfile channel0(const sss::ProfileRGB& p) { return p[0]; }

sss::BurleyParameterisation burley_parameterisation(const std::string& name) {
  if (name == "volume-mfp") return sss::BurleyParameterisation::VolumeMeanFreePath;
  if (name == "diffuse-mfp") return sss::BurleyParameterisation::DiffuseMeanFreePath;
  if (name == "searchlight") return sss::BurleyParameterisation::Searchlight;
  throw py::value_error(
      fmt::format("parameterisation must be 'volume-mfp', 'diffuse-mfp' or 'searchlight', got '{}'", name));
}

sss::WalkSampling walk_sampling(const std::string& name) {
  if (name == "classical") return sss::WalkSampling::Classical;
  if (name == "dwivedi") return sss::WalkSampling::Dwivedi;
  if (name == "mis") return sss::WalkSampling::Mis;
  throw py::value_error(fmt::format("sampling must be 'classical', 'dwivedi' or 'mis', got '{}'", name));
}

}  // namespace

void bind_sss(py::module_& m) {
  py::class_<RadialProfile>(m, "Profile", R"(A radial diffusion profile R(r) of one channel (lengths in scene units).

Made by Profile.burley, .dipole, .cubic, .gaussian or .skin. eval, sample and pdf take
NumPy arrays or numbers.)")
      .def_static(
          "burley",
          [](double albedo, double mfp, const std::string& p) {
            return RadialProfile(sss::BurleyProfile(albedo, mfp, burley_parameterisation(p)));
          },
          py::arg("albedo"), py::arg("mfp"), py::arg("parameterisation") = "volume-mfp",
          "Christensen & Burley 2015: surface albedo A in [0, 1], mean free path l (its meaning: 'volume-mfp', "
          "'diffuse-mfp' or 'searchlight').")
      .def_static(
          "dipole",
          [](double albedo, double mfp, double eta) {
            return channel0(sss::make_dipole_rgb(RGB(float(albedo)), RGB(float(mfp)), eta));
          },
          py::arg("albedo"), py::arg("mfp"), py::arg("eta") = 1.0,
          "Jensen et al. 2001's dipole for surface albedo A and mean free path l, relative index eta.")
      .def_static(
          "cubic", [](double albedo, double radius) { return RadialProfile(sss::CubicProfile(radius, albedo)); },
          py::arg("albedo"), py::arg("radius"), "The cubic falloff of radius R (Arnold, Cycles), albedo A.")
      .def_static(
          "gaussian",
          [](double albedo, double variance) { return RadialProfile(sss::GaussianProfile(variance, albedo)); },
          py::arg("albedo"), py::arg("variance"), "A normalized 2-D Gaussian of variance v, weight A.")
      .def_static(
          "skin",
          [](double scene_units_per_mm, int channel) {
            if (channel < 0 || channel > 2) throw py::value_error("channel must be 0, 1 or 2 (R, G, B)");
            return sss::make_skin_rgb(scene_units_per_mm)[channel];
          },
          py::arg("scene_units_per_mm") = 1.0, py::arg("channel") = 0,
          "d'Eon & Luebke's six-Gaussian skin (GPU Gems 3, table 14-1), one channel.")
      .def(
          "eval",
          [](const RadialProfile& p, const Doubles& r) { return map_array(r, [&](double x) { return p.eval(x); }); },
          py::arg("r"), "R(r), an area density on the surface.")
      .def(
          "sample",
          [](const RadialProfile& p, const Doubles& xi) {
            return map_array(xi, [&](double x) { return p.sample_radius(x); });
          },
          py::arg("xi"), "A radius distributed as pdf(r), for xi uniform in [0, 1).")
      .def(
          "pdf",
          [](const RadialProfile& p, const Doubles& r) {
            return map_array(r, [&](double x) { return p.pdf_radius(x); });
          },
          py::arg("r"), "The radial density of sample() (zero beyond r_max()).")
      .def("albedo", &RadialProfile::albedo, "The integral of R over the plane.")
      .def(
          "r_max", [](const RadialProfile& p, std::optional<double> f) { return f ? p.r_max(*f) : p.r_max(); },
          py::arg("energy_fraction") = py::none(),
          "The truncation radius of sample(), or the radius inside which energy_fraction of the energy lies.");

  m.def(
      "simulate_halfspace",
      [](double albedo, double sigma_t, double g, double eta, bool exit_matched, const std::string& incidence,
         uint64_t paths, uint64_t seed, double r_max, int bins, const std::string& sampling) {
        sss::HalfspaceConfig c;
        c.albedo = albedo;
        c.sigma_t = sigma_t;
        c.g = g;
        c.eta = eta;
        c.exit_matched = exit_matched;
        sss::parse_incidence(incidence, c.incidence, c.incidence_angle);
        c.paths = paths;
        c.seed = seed;
        c.bins = sss::RadialBins::linear(r_max, bins);
        c.sampling = walk_sampling(sampling);
        sss::validate(c);
        sss::HalfspaceResult r;
        std::atomic<bool> never{false};  // the simulation has no cancel: Ctrl-C is raised when it ends
        auto error = run_interruptible([&] { r = sss::simulate_halfspace(c); }, never, nullptr);
        if (error) throw *error;
        py::dict d;
        d["albedo"] = r.albedo;
        d["albedo_stderr"] = r.albedo_stderr;
        d["albedo_per_entering"] = r.albedo_per_entering();
        d["albedo_per_entering_stderr"] = r.albedo_per_entering_stderr();
        d["specular"] = r.specular;
        d["absorbed"] = r.absorbed;
        d["absorbed_stderr"] = r.absorbed_stderr;
        d["truncated_weight"] = r.truncated_weight;
        d["r_lo"] = py::array(py::cast(r.r_lo));
        d["r_hi"] = py::array(py::cast(r.r_hi));
        d["R"] = py::array(py::cast(r.R));
        d["R_stderr"] = py::array(py::cast(r.R_stderr));
        d["paths"] = r.paths;
        d["mean_collisions"] = r.mean_collisions;
        d["seconds"] = r.seconds;
        return d;
      },
      py::kw_only(), py::arg("albedo") = 0.5, py::arg("sigma_t") = 1.0, py::arg("g") = 0.0, py::arg("eta") = 1.0,
      py::arg("exit_matched") = false, py::arg("incidence") = "normal", py::arg("paths") = 100000, py::arg("seed") = 1,
      py::arg("r_max") = 16.0, py::arg("bins") = 64, py::arg("sampling") = "classical",
      R"(Brute-force Monte Carlo of light in a homogeneous half-space below a flat boundary
(the ground truth of the diffusion profiles).

albedo: single-scattering albedo sigma_s/sigma_t; sigma_t: extinction; g: HG anisotropy;
eta: relative index (1: index-matched); exit_matched: refract at entry only;
incidence: 'normal', 'diffuse' or 'angle:DEG'; sampling: 'classical', 'dwivedi', 'mis'.
Returns a dict: albedo (+ albedo_stderr), albedo_per_entering, specular, absorbed,
truncated_weight, the radial profile R over bins [r_lo, r_hi) with R_stderr, paths,
mean_collisions, seconds. The same arguments give the same result on any thread count.)");

  m.def(
      "chandrasekhar_albedo",
      [](double alpha, std::optional<double> mu0) {
        if (!(alpha >= 0 && alpha <= 1)) throw py::value_error("alpha must lie in [0, 1]");
        const sss::HFunction h(alpha);
        return mu0 ? sss::halfspace_albedo_collimated(h, *mu0) : sss::halfspace_albedo_diffuse(h);
      },
      py::arg("alpha"), py::arg("mu0") = py::none(),
      "The exact albedo of an index-matched isotropic half-space of single-scattering albedo alpha (Chandrasekhar's "
      "H-function): for collimated light at cosine mu0, or for diffuse light when mu0 is None.");

  py::class_<sss::AlbedoInversion>(m, "AlbedoInversion",
                                   "Surface albedo A <-> single-scattering albedo alpha for a boundary (eta, g), "
                                   "tabulated with the half-space simulator (cached on disk).")
      .def(py::init([](double eta, double g, bool exit_matched, int size, uint64_t paths_per_node) {
             sss::AlbedoTableConfig c;
             c.eta = eta;
             c.g = g;
             c.exit_matched = exit_matched;
             c.size = size;
             c.paths_per_node = paths_per_node;
             py::gil_scoped_release release;
             return std::make_unique<sss::AlbedoInversion>(c);
           }),
           py::kw_only(), py::arg("eta") = 1.0, py::arg("g") = 0.0, py::arg("exit_matched") = false,
           py::arg("size") = 32, py::arg("paths_per_node") = 100000)
      .def(
          "surface_albedo",
          [](const sss::AlbedoInversion& inv, const Doubles& alpha) {
            return map_array(alpha, [&](double a) { return inv.surface_albedo(a); });
          },
          py::arg("alpha"), "A(alpha): the surface albedo of single-scattering albedo alpha.")
      .def(
          "single_scattering_albedo",
          [](const sss::AlbedoInversion& inv, const Doubles& A) {
            return map_array(A, [&](double a) { return inv.single_scattering_albedo(a); });
          },
          py::arg("A"), "alpha(A): the inverse of surface_albedo.")
      .def_property_readonly("node_alphas", [](const sss::AlbedoInversion& inv) { return inv.node_alphas(); })
      .def_property_readonly("node_albedos", [](const sss::AlbedoInversion& inv) { return inv.node_albedos(); })
      .def_property_readonly("from_cache", [](const sss::AlbedoInversion& inv) { return inv.from_cache(); });
}

}  // namespace dermis::python
