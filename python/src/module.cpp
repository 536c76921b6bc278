// hilite._hilite: the C++ half of the Python module (python/hilite/ is the other). It takes scenes as
// lists of (parameter, text, origin) — the CLI's own spelling, which the Python half makes from keywords —
// so every value is read and checked by scene::resolve exactly as on the command line. GL work runs on one
// thread owned by the module (measurement/gl_worker.hpp), with the GIL released.

#include "convert.hpp"
#include "measurement/gl_worker.hpp"

#include "brdf/bihemispherical.hpp"
#include "brdf/integrate.hpp"
#include "brdf/merl.hpp"
#include "core/text.hpp"
#include "experiments/experiment.hpp"
#include "experiments/results.hpp"
#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/error.hpp"
#include "hilite/experiments/bounces.hpp"
#include "hilite/experiments/fit.hpp"
#include "hilite/experiments/run.hpp"
#include "hilite/experiments/slice.hpp"
#include "hilite/hilite.hpp"
#include "io/image_io.hpp"
#include "measurement/shader_probe.hpp"
#include "render/renderer.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>

namespace py = pybind11;
using namespace hilite;
using hilite::python::Items;

namespace {

measurement::GlWorker& worker() {
    static measurement::GlWorker* w = new measurement::GlWorker();  // stopped by _shutdown (atexit), never destroyed
    return *w;
}

/// A context of another backend than the one the module already made is refused, not silently ignored.
void checkBackend(measurement::Session& s, const scene::Resolved& r) {
    const auto have = s.glBackend();
    if (!have || r.backend.empty() || r.backend == "auto") return;
    if (scene::backendOf(r) != *have)
        throw InputError(r.values.where("gl_backend") + ": the module's GL context is " + gl::toString(*have) +
                         " (made by the first GL call of this process); a process holds one");
}

/// Every scene is resolved (and so checked) before the first is measured; a measured table is then let go and
/// read again when its scene is measured, so a list of tables is held one at a time (merl::load keeps the 2 most
/// recent), as `hilite run` holds a folder sweep's: 6 tables peaked at 875 MB, all held to the end.
py::list measureScenes(const std::vector<Items>& scenes) {
    std::vector<nlohmann::json> rows;
    {
        py::gil_scoped_release release;
        std::vector<scene::Resolved> all;
        std::vector<bool> table;
        for (const Items& items : scenes) {
            all.push_back(scene::resolve(python::values(items), scene::Purpose::Measure));
            table.push_back(all.back().scene.brdf.isMeasured());
            all.back().scene.brdf.measured.reset();
            all.back().scene.brdf.rgl.reset();
        }
        worker().run([&](measurement::Session& s) {
            for (size_t i = 0; i < all.size(); ++i) {
                scene::Resolved one =
                    table[i] ? scene::resolve(python::values(scenes[i]), scene::Purpose::Measure) : std::move(all[i]);
                if (!one.reference && !one.setup.cpu) {
                    checkBackend(s, one);
                    s.rendererFor(one);  // a .brdf's probe, before its first row
                }
                const std::vector<double> angles = one.angles;
                for (double angle : angles) {
                    one.scene.light.incidenceDeg = angle;
                    nlohmann::json j = measurement::toJson(s.measureOne(one));
                    experiments::nameNonFinite(j);  // as `hilite measure --json` writes it
                    rows.push_back(std::move(j));
                }
            }
        });
    }
    py::list out;
    for (const auto& j : rows) out.append(python::toPython(j));
    return out;
}

/// `hilite fit --json` in process: one object per model (experiments/fit.hpp), every scene resolved first.
py::list fitScene(const Items& items, const std::vector<std::string>& models, const std::vector<double>& thresholds,
                  const std::vector<double>& weights, bool anisotropy, bool f0, const std::string& geometry,
                  const std::string& fresnel, const std::string& diffuse, const std::string& rankBy, bool color,
                  int maxEvaluations) {
    std::vector<std::string> rows;
    {
        py::gil_scoped_release release;
        const scene::Values values = python::values(items);
        experiments::FitOptions o;
        o.models = models;
        o.thresholds = thresholds;
        o.weights = weights;
        o.anisotropy = anisotropy;
        o.f0 = f0;
        o.geometry = geometry;
        o.fresnel = fresnel;
        o.diffuse = diffuse;
        o.rankBy = rankBy;
        o.color = color;
        o.maxEvaluations = maxEvaluations;
        experiments::checkFitScenes(values, o);
        const scene::Resolved target = scene::resolve(values);
        worker().run([&](measurement::Session& s) {
            if (!target.reference && !target.setup.cpu) {
                checkBackend(s, target);
                s.rendererFor(target);  // a .brdf target's probe, before anything is measured
            }
            const experiments::FitResult r = experiments::fitModels(s, values, o);
            for (const auto& m : r.fits) rows.push_back(experiments::toJson(r, m).dump());
        });
    }
    py::list out;
    for (const auto& j : rows) out.append(python::toPython(nlohmann::json::parse(j)));
    return out;
}

/// The radiance (H, W, 3) float32, row 0 the top; with `maps` the measurement view's u, v (deg) and pixel
/// area (deg^2) from the Output::Measure render of the same camera.
py::tuple renderScene(const Items& items, bool maps) {
    ImageF color, measureImg;
    {
        py::gil_scoped_release release;
        const scene::Resolved r = scene::resolve(python::values(items), scene::Purpose::Render);
        if (r.angles.size() > 1)
            throw InputError(r.values.where("incidence") + ": render takes one angle (got '" +
                             r.values.text("incidence") + "')");
        if (maps && r.view != scene::View::Measure)
            throw InputError("maps: the (u, v) and pixel-area maps belong to view='measure' (got view='photo')");
        const PinholeCamera camera = scene::viewCamera(r, r.view, r.setup.width, r.setup.height);
        worker().run([&](measurement::Session& s) {
            checkBackend(s, r);
            render::Renderer& renderer = s.rendererFor(r);
            color = renderer.render(r.scene, camera, render::Output::Color);
            if (maps) measureImg = renderer.render(r.scene, camera, render::Output::Measure);
        });
        size_t nonFinite = 0;
        for (float v : color.data) nonFinite += !std::isfinite(v);
        if (nonFinite)
            throw InputError("render: " + std::to_string(nonFinite) +
                             " pixel values are NaN or Inf (the BRDF is not "
                             "finite there, e.g. a lobe infinite at its peak)");
    }
    const py::array_t<float> img = python::topDown(color, {0, 1, 2});
    if (!maps) return py::make_tuple(img, py::none());
    constexpr double deg = 180.0 / M_PI;
    py::dict m;
    m["u_deg"] = python::topDownScaled(measureImg, 1, deg);
    m["v_deg"] = python::topDownScaled(measureImg, 2, deg);
    m["area_deg2"] = python::topDownScaled(measureImg, 3, deg * deg);
    m["luminance"] = python::topDownScaled(measureImg, 0, 1.0);
    return py::make_tuple(img, m);
}

py::array_t<double> rgbRows(const std::vector<dvec3>& v) {
    py::array_t<double> out({py::ssize_t(v.size()), py::ssize_t(3)});
    auto a = out.mutable_unchecked<2>();
    for (size_t i = 0; i < v.size(); ++i)
        for (int c = 0; c < 3; ++c) a(py::ssize_t(i), c) = v[i][c];
    return out;
}

py::array_t<double> fresnelOf(const Items& items, bool spectral) {
    std::vector<dvec3> v;
    {
        py::gil_scoped_release release;
        const scene::Values values = python::values(items);
        const brdf::Params p = scene::resolveFresnel(values, spectral);
        for (double t : scene::resolve(values, scene::Purpose::Brdf).angles) {
            double c, s;
            cosSinDeg(t, c, s);
            v.push_back(brdf::fresnel(p, c));
        }
    }
    return rgbRows(v);
}

py::array_t<double> albedoOf(const Items& items) {
    std::vector<dvec3> v;
    {
        py::gil_scoped_release release;
        const scene::Resolved r = scene::resolve(python::values(items), scene::Purpose::Brdf);
        for (double t : r.angles) v.push_back(brdf::albedo(r.scene.brdf, t, r.scene.light.azimuthDeg));
    }
    return rgbRows(v);
}

/// `hilite brdf bounces --json` in process: a row per incidence (experiments/bounces.hpp); the settings (named
/// as the [bounces] keys) and the scene are checked before the first path.
py::list bouncesOf(const Items& items, long paths, int batches, uint64_t seed, int texels, int bumpsPerTile,
                   const std::string& surface) {
    std::vector<std::string> rows;
    {
        py::gil_scoped_release release;
        experiments::BounceSettings s;
        const auto kind = micro::parseTracedSurface(surface);
        if (!kind) throw InputError("surface: '" + surface + "' is not a traced surface (allowed: hermite, bilinear)");
        s.options.surface = *kind;
        s.options.paths = paths;
        s.options.batches = batches;
        s.options.seed = seed;
        s.texels = texels;
        s.bumpsPerTile = bumpsPerTile;
        experiments::checkBounceSettings(s, false);
        const scene::Values values = python::values(items);
        experiments::resolveBounceScene(values);
        for (const auto& study : experiments::studyBounces(values, s))
            rows.push_back(experiments::bounceRow(study).dump());
    }
    py::list out;
    for (const auto& j : rows) out.append(python::toPython(nlohmann::json::parse(j)));
    return out;
}

/// hilite.brdf.slice: each (label, items) a curve, the incidences those of the first curve's items.
py::list sliceOf(const std::vector<std::pair<std::string, Items>>& curves, double step) {
    std::vector<std::string> rows;
    {
        py::gil_scoped_release release;
        std::vector<experiments::SliceCurve> cs;
        for (const auto& [label, items] : curves)
            cs.push_back({label, scene::resolve(python::values(items), scene::Purpose::Brdf)});
        if (cs.empty()) throw InputError("slice: give at least one BRDF");
        for (const auto& p : experiments::brdfSlices(cs, cs.front().scene.angles, step))
            rows.push_back(experiments::toJson(p).dump());
    }
    py::list out;
    for (const auto& j : rows) out.append(python::toPython(nlohmann::json::parse(j)));
    return out;
}

py::array_t<double> bihemispherical(const Items& items) {
    std::vector<dvec3> v;
    {
        py::gil_scoped_release release;
        v.push_back(
            brdf::bihemisphericalAlbedo(scene::resolve(python::values(items), scene::Purpose::Brdf).scene.brdf));
    }
    return rgbRows(v);
}

double normalizationOf(const Items& items) {
    py::gil_scoped_release release;
    const scene::Resolved r = scene::resolve(python::values(items), scene::Purpose::Brdf);
    if (!brdf::isMicrofacet(r.scene.brdf.model))
        throw InputError(r.values.where("model") +
                         ": normalization needs an NDF: blinn, gaussian, beckmann, ggx, "
                         "tabulated (got '" +
                         r.values.text("model") + "')");
    return brdf::ndfIntegral(r.scene.brdf);
}

/// f(wi, wo) for N pairs of unit directions (local frame, n = +z), the double path.
py::array_t<double> evalBrdf(const Items& items, py::array_t<double, py::array::c_style | py::array::forcecast> wi,
                             py::array_t<double, py::array::c_style | py::array::forcecast> wo) {
    if (wi.ndim() != 2 || wi.shape(1) != 3 || wo.ndim() != 2 || wo.shape(1) != 3 || wi.shape(0) != wo.shape(0))
        throw InputError("eval: wi and wo must be (N, 3) arrays of the same N");
    const py::ssize_t n = wi.shape(0);
    py::array_t<double> out({n, py::ssize_t(3)});
    const double* a = wi.data();
    const double* b = wo.data();
    double* o = out.mutable_data();
    py::gil_scoped_release release;
    const scene::Resolved r = scene::resolve(python::values(items), scene::Purpose::Brdf);
    for (py::ssize_t i = 0; i < n; ++i) {
        const dvec3 in(a[3 * i], a[3 * i + 1], a[3 * i + 2]), out3(b[3 * i], b[3 * i + 1], b[3 * i + 2]);
        // Directions of another length would be evaluated as if unit (the terms assume it): refuse them.
        for (const auto& [name, w] : {std::pair<const char*, dvec3>{"wi", in}, {"wo", out3}})
            if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z) ||
                std::abs(glm::length(w) - 1.0) > 1e-6)
                throw InputError(std::string("eval: ") + name + "[" + std::to_string(i) +
                                 "] is not a finite unit vector (|w| - 1 must be within 1e-6)");
        const dvec3 f = brdf::evaluate(r.scene.brdf, in, out3);
        o[3 * i] = f.x, o[3 * i + 1] = f.y, o[3 * i + 2] = f.z;
    }
    return out;
}

py::dict resolveColumns(const Items& items, const std::string& purpose) {
    nlohmann::json j;
    {
        py::gil_scoped_release release;
        const scene::Purpose p = purpose == "render" ? scene::Purpose::Render
                                 : purpose == "brdf" ? scene::Purpose::Brdf
                                                     : scene::Purpose::Measure;
        const scene::Resolved r = scene::resolve(python::values(items), p);
        j = scene::parameterColumns(r);
        j["angles"] = r.angles;
        j["effects"] = render::activeEffects(r.scene);
    }
    return python::toPython(j).cast<py::dict>();
}

void writeScene(const std::string& path, const Items& items) {
    const std::string text = scene::sceneToml(python::values(items));
    py::gil_scoped_release release;
    io::checkWritable(path, "path");
    io::writeFileAtomic(path, text);
}

/// An experiment run makes a GL context of its own: the module's is made current again afterwards, even
/// when the run throws (a failure to do so surfaces at the next render).
struct CurrentAgain {
    measurement::Session& session;
    ~CurrentAgain() {
        try {
            session.makeCurrent();
        } catch (...) {
        }
    }
};

py::dict runExperiment(const std::string& experiment, const std::string& out, bool resume, const std::string& shard,
                       const std::string& backend, bool fsyncEachRow) {
    experiments::RunSummary s;
    {
        py::gil_scoped_release release;
        experiments::RunOptions o;
        experiments::parseShard(shard, o.shardK, o.shardN, "shard");
        o.experiment = experiment, o.out = out, o.resume = resume, o.backend = backend, o.outName = "out";
        o.fsyncEachRow = fsyncEachRow;
        worker().run([&](measurement::Session& session) {
            const CurrentAgain restore{session};
            s = experiments::runExperiment(o);
        });
    }
    py::dict d;
    d["name"] = s.name, d["dir"] = s.dir, d["configurations"] = s.configurations, d["measured"] = s.measured;
    d["seconds"] = s.seconds, d["finalized"] = s.finalized;
    return d;
}

py::dict summaryDict(const experiments::RunSummary& s) {
    py::dict d;
    d["name"] = s.name, d["dir"] = s.dir, d["configurations"] = s.configurations, d["measured"] = s.measured;
    d["seconds"] = s.seconds, d["finalized"] = s.finalized;
    return d;
}

/// Runs `job` on the GL thread, the module's context current again after it; the GIL released meanwhile.
template <class F>
void onGlThread(F&& job) {
    py::gil_scoped_release release;
    worker().run([&](measurement::Session& session) {
        const CurrentAgain restore{session};
        job();
    });
}

/// An owned object whose GL resources must go on the GL thread (a context is released where it is current);
/// at interpreter exit, when that thread has stopped, it is left to the process's end.
template <class T>
void dropOnGlThread(std::unique_ptr<T>& p) {
    if (!p) return;
    try {
        onGlThread([&] { p.reset(); });
    } catch (...) {
        (void)p.release();
    }
}

/// hilite.run(..., client=): the client's side, rows fed in by the workers' results (python/hilite/_dask.py).
class PyDistributedRun {
public:
    PyDistributedRun(const std::string& experiment, const std::string& out, bool resume, const std::string& shard,
                     const std::string& backend, bool fsyncEachRow) {
        experiments::RunOptions o;
        experiments::parseShard(shard, o.shardK, o.shardN, "shard");
        o.experiment = experiment, o.out = out, o.resume = resume, o.backend = backend, o.outName = "out";
        o.fsyncEachRow = fsyncEachRow;
        onGlThread([&] { m_run = std::make_unique<experiments::DistributedRun>(o); });
    }
    ~PyDistributedRun() { dropOnGlThread(m_run); }
    experiments::DistributedRun& get() {
        if (!m_run) throw InputError("run: this run has been closed");
        return *m_run;
    }
    void append(const std::vector<std::string>& rows) {
        py::gil_scoped_release release;
        for (const auto& r : rows) get().append(r);
    }
    py::dict finish() {
        experiments::RunSummary s;
        onGlThread([&] {  // finalize renders the contact sheet: on the GL thread
            s = get().finish();
            m_run.reset();
        });
        return summaryDict(s);
    }
    size_t close() {  // the rows appended made durable, the lock released; how many were appended
        const size_t n = m_run ? m_run->appended() : 0;
        dropOnGlThread(m_run);
        return n;
    }

private:
    std::unique_ptr<experiments::DistributedRun> m_run;
};

/// A Dask worker's side: the experiment loaded once per worker process, configurations measured by index.
class PyMeasurer {
public:
    PyMeasurer(const std::string& experiment, const std::string& backend) {
        onGlThread([&] { m_m = std::make_unique<experiments::ConfigurationMeasurer>(experiment, backend); });
    }
    ~PyMeasurer() { dropOnGlThread(m_m); }
    std::vector<std::string> measure(const std::vector<size_t>& indices) {
        std::vector<std::string> rows;
        onGlThread([&] {
            for (size_t i : indices) rows.push_back(m_m->measure(i));
        });
        return rows;
    }
    size_t configurations() const { return m_m->configurations(); }

private:
    std::unique_ptr<experiments::ConfigurationMeasurer> m_m;
};

py::dict mergeShards(const std::vector<std::string>& shards, const std::string& out, const std::string& backend) {
    experiments::MergeSummary s;
    {
        py::gil_scoped_release release;
        worker().run([&](measurement::Session& session) {
            const CurrentAgain restore{session};
            s = experiments::mergeShards(shards, out, backend, "out");
        });
    }
    py::dict d;
    d["dir"] = s.dir, d["rows"] = s.rows, d["expected"] = s.expected, d["shards"] = s.shards;
    return d;
}

py::list registryList() {
    py::list out;
    for (const scene::Param& p : scene::registry()) {
        py::dict d;
        d["name"] = p.name;
        d["table"] = scene::toString(p.table);
        d["kind"] = scene::kindName(p.kind);
        d["default"] = p.def;
        d["lo"] = p.lo, d["hi"] = p.hi, d["open_lo"] = p.openLo, d["open_hi"] = p.openHi;
        d["choices"] = p.choices;
        d["unit"] = p.unit;
        d["help"] = p.help;
        d["applies_to"] = p.appliesTo;
        d["column"] = p.column;
        d["automatic"] = p.automatic;
        d["allowed"] = p.allowed();
        d["flag"] = p.flag();
        out.append(d);
    }
    return out;
}

}  // namespace

PYBIND11_MODULE(_hilite, m) {
    m.doc() = "hilite's C++ core (use the `hilite` package, not this module)";
    // InputError: bad input, the CLI's one-line message (a ValueError). MachineError: the machine failed.
    py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
    py::register_exception<SystemError>(m, "MachineError", PyExc_RuntimeError);
    m.attr("version") = kVersionString;
    m.attr("max_scenes") = experiments::kMaxConfigurations;  // a sweep larger is refused, as `hilite run` does
    m.def("registry", &registryList);
    // the measurement fields of a row, in results.csv's order: the stubs' typed row (python/gen_stubs.py)
    m.def("measurement_columns", &measurement::measurementColumns);
    m.def("check", [](const std::string& name, const std::string& text) {
        const scene::Param* p = scene::find(name);
        return p ? scene::check(*p, text) : std::string("unknown parameter");
    });
    m.def("did_you_mean", &didYouMean, py::arg("word"), py::arg("candidates"));  // the CLI's own suggestion
    m.def("measure", &measureScenes, py::arg("scenes"));
    m.def("render", &renderScene, py::arg("items"), py::arg("maps"));
    m.def("fit", &fitScene, py::arg("items"), py::arg("models"), py::arg("thresholds"), py::arg("weights"),
          py::arg("anisotropy"), py::arg("f0"), py::arg("geometry"), py::arg("fresnel"), py::arg("diffuse"),
          py::arg("rank_by"), py::arg("color"), py::arg("max_evaluations"));
    m.def("fit_defaults", [] {  // the one set of defaults the CLI and experiment files use too
        const experiments::FitOptions o;
        py::dict d;
        d["models"] = o.models;
        d["thresholds"] = o.thresholds;
        d["fit_anisotropy"] = o.anisotropy;
        d["fit_f0"] = o.f0;
        d["fit_geometry"] = o.geometry;
        d["fit_fresnel"] = o.fresnel;
        d["fit_diffuse"] = o.diffuse;
        d["rank_by"] = o.rankBy;
        d["fit_color"] = o.color;
        d["max_evaluations"] = o.maxEvaluations;
        return d;
    });
    m.def("fresnel", &fresnelOf, py::arg("items"), py::arg("spectral"));
    m.def("albedo", &albedoOf, py::arg("items"));
    m.def("bihemispherical_albedo", &bihemispherical, py::arg("items"));
    m.def("bounces", &bouncesOf, py::arg("items"), py::arg("paths"), py::arg("batches"), py::arg("seed"),
          py::arg("texels"), py::arg("bumps_per_tile"), py::arg("surface"));
    m.def("normalization", &normalizationOf, py::arg("items"));
    m.def("slice", &sliceOf, py::arg("curves"), py::arg("step"));
    m.def("eval", &evalBrdf, py::arg("items"), py::arg("wi"), py::arg("wo"));
    m.def("resolve", &resolveColumns, py::arg("items"), py::arg("purpose"));
    m.def("scene_toml", [](const Items& items) { return scene::sceneToml(python::values(items)); });
    m.def("parse_scene", [](const std::string& text, const std::string& name) {
        return python::items(scene::parseSceneToml(text, name));
    });
    m.def("load_scene", [](const std::string& path) { return python::items(scene::loadSceneFile(path)); });
    m.def("write_scene", &writeScene, py::arg("path"), py::arg("items"));
    m.def("run", &runExperiment, py::arg("experiment"), py::arg("out"), py::arg("resume"), py::arg("shard"),
          py::arg("backend"), py::arg("fsync_each_row"));
    m.def("merge", &mergeShards, py::arg("shards"), py::arg("out"), py::arg("backend"));
    py::class_<PyDistributedRun>(m, "_DistributedRun")
        .def(py::init<const std::string&, const std::string&, bool, const std::string&, const std::string&, bool>(),
             py::arg("experiment"), py::arg("out"), py::arg("resume"), py::arg("shard"), py::arg("backend"),
             py::arg("fsync_each_row"))
        .def_property_readonly("experiment_path", [](PyDistributedRun& r) { return r.get().experimentPath(); })
        .def_property_readonly("dir", [](PyDistributedRun& r) { return r.get().dir(); })
        .def("todo", [](PyDistributedRun& r) { return r.get().todo(); })
        .def("append", &PyDistributedRun::append, py::arg("rows"))
        .def("finish", &PyDistributedRun::finish)
        .def("close", &PyDistributedRun::close);
    py::class_<PyMeasurer>(m, "_Measurer")
        .def(py::init<const std::string&, const std::string&>(), py::arg("experiment"), py::arg("backend"))
        .def("measure", &PyMeasurer::measure, py::arg("indices"))
        .def_property_readonly("configurations", &PyMeasurer::configurations);
    m.def("set_probe_executable", &measurement::setProbeExecutable);
    m.def("gl_renderer", [] {
        std::string name;
        py::gil_scoped_release release;
        worker().run([&](measurement::Session& s) { name = s.glRenderer(); });
        return name;
    });
    m.def("_measured_tables_held", [] {  // (now, peak) since the last call: tests of a list of tables' memory
        const brdf::merl::Held h = brdf::merl::tablesHeld(true);
        return std::make_pair(h.now, h.peak);
    });
    m.def("worker_thread_id", [] { return worker().threadId(); });
    m.def("_shutdown", [] {
        py::gil_scoped_release release;
        worker().stop();
    });
}
