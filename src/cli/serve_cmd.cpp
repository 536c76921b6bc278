// `hilite serve`: the highlight explorer in the browser. A local HTTP server (Debian's cpp-httplib) over the
// library in process: a JSON API under /api/ (registry, resolve, match, measure, render, slice, explain,
// results, files) and the page (HTML, CSS, JS, no build step) from the share folder's serve/.
//
// Safe by default: it binds to loopback; files are served only from the page folder and the results root
// (no '..', no absolute paths, no symlink leading out: canonical paths checked); request bodies and render
// sizes are capped; bad JSON or values are answered 400 with the CLI's one-line message. GL work runs on one
// thread that owns the Session (measurement/gl_worker.hpp): one render at a time, the others queue, and a
// request finding the queue full is answered 503 at once.

#include "cli/commands.hpp"
#include "cli/scene_toml.hpp"
#include "core/install_paths.hpp"
#include "core/text.hpp"
#include "experiments/experiment.hpp"
#include "experiments/results.hpp"
#include "hilite/brdf/params.hpp"
#include "hilite/core/chart.hpp"
#include "hilite/core/error.hpp"
#include "hilite/core/math.hpp"
#include "hilite/experiments/slice.hpp"
#include "hilite/measurement/measure_scene.hpp"
#include "hilite/measurement/row.hpp"
#include "hilite/measurement/session.hpp"
#include "hilite/render/scene.hpp"
#include "hilite/scene/registry.hpp"
#include "io/image_io.hpp"
#include "measurement/gl_worker.hpp"
#include "render/renderer.hpp"
#include "render/shader_source.hpp"

#include <httplib.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <sys/socket.h>

namespace hilite::cli {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr size_t kMaxBody = 64 * 1024;      ///< request body cap (413 above)
constexpr long kMaxPixels = 1024 * 1024;    ///< render / measurement size cap (width x height x supersample^2)
constexpr size_t kMaxAngles = 181;          ///< incidence angles per measure request
constexpr size_t kMaxFileBytes = 64 << 20;  ///< a file served from the results root
constexpr size_t kMaxRows = 20000;          ///< rows of a result folder sent
constexpr int kHttpThreads = 16;            ///< cpp-httplib's worker threads
constexpr int kEllipsePoints = 72;          ///< points of the drawn ellipse
constexpr const char* kPageDir = "serve";   ///< under the share folder
constexpr const char* kDefaultResults = "results";
/// cpp-httplib compresses "application/json" and "text/..." answers for a browser (brotli at its slowest
/// quality: 100 ms for a render's 70 KB, more than the render itself); with the charset named it does not.
constexpr const char* kJson = "application/json; charset=utf-8";

struct ServeFlags {
    std::string host = "127.0.0.1";
    int port = 8765;
    std::string results = kDefaultResults;
    int queue = 8;  ///< GL jobs queued or running at most (503 above)
    bool log = false;
};

std::atomic<bool> g_log{false};  ///< --log

/// An answer other than 200 with its one line.
struct HttpError {
    int status;
    std::string message;
};

bool within(const fs::path& p, const fs::path& root) {
    auto r = root.begin(), q = p.begin();
    for (; r != root.end(); ++r, ++q)
        if (q == p.end() || *q != *r) return false;
    return true;
}

/// `rel` (a URL path, already percent-decoded, or a file parameter's value) under `root`: refused (403) when
/// it is absolute, holds '..' or a control character, or its canonical path (symlinks resolved) leaves the
/// root; 404 when it does not exist.
fs::path confined(const fs::path& root, const std::string& rel, const std::string& what) {
    for (char c : rel)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            throw HttpError{403, what + ": refused: a control character"};
    const fs::path p(rel);
    if (p.is_absolute() || rel.rfind('/', 0) == 0) throw HttpError{403, what + ": refused: an absolute path"};
    for (const auto& part : p)
        if (part == "..") throw HttpError{403, what + ": refused: '..' in the path"};
    std::error_code ec;
    const fs::path full = fs::weakly_canonical(root / p, ec);
    if (ec || !within(full, root)) throw HttpError{403, what + ": refused: it leads outside the served folder"};
    if (!fs::exists(full, ec)) throw HttpError{404, what + ": not found"};
    return full;
}

/// The type a file is served as: the page's own HTML, JS and CSS run; a file of the results root never does (a
/// PNG, JSON or bytes: no text/ type either, which cpp-httplib would compress, slowly, up to 64 MiB of it).
std::string contentType(const fs::path& p, bool page) {
    const std::string e = p.extension().string();
    if (page && e == ".html") return "text/html; charset=utf-8";
    if (page && e == ".js") return "text/javascript; charset=utf-8";
    if (page && e == ".css") return "text/css; charset=utf-8";
    if (e == ".png") return "image/png";
    if (e == ".json") return kJson;
    return "application/octet-stream";
}

std::string readFile(const fs::path& p) {
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) throw HttpError{404, "not a file"};
    if (fs::file_size(p, ec) > kMaxFileBytes) throw HttpError{413, "file over the server's cap of 64 MiB"};
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    if (!in && !in.eof()) throw HttpError{404, "cannot read the file"};
    return s.str();
}

json registryJson() {
    json out = json::array();
    for (const scene::Param& p : scene::registry())
        out.push_back({{"name", p.name},
                       {"table", scene::toString(p.table)},
                       {"kind", scene::kindName(p.kind)},
                       {"default", p.def},
                       {"lo", p.lo},
                       {"hi", p.hi},
                       {"open_lo", p.openLo},
                       {"open_hi", p.openHi},
                       {"choices", p.choices},
                       {"unit", p.unit},
                       {"help", p.help},
                       {"applies_to", p.appliesTo},
                       {"allowed", p.allowed()},
                       {"automatic", p.automatic},
                       {"flag", p.flag()}});
    return out;
}

/// The body as a JSON object whose keys are among `keys`.
json parseBody(const httplib::Request& req, const std::vector<std::string>& keys) {
    json j;
    try {
        j = json::parse(req.body.empty() ? std::string("{}") : req.body);
    } catch (const json::exception& e) {
        throw InputError(std::string("request body: not JSON: ") + e.what());
    }
    if (!j.is_object()) throw InputError("request body: a JSON object expected");
    for (const auto& item : j.items())
        if (std::find(keys.begin(), keys.end(), item.key()) == keys.end()) {
            const std::string hint = didYouMean(item.key(), keys);
            throw InputError("request body: unknown key '" + printable(item.key()) + "'" +
                             (hint.empty() ? "" : " (did you mean '" + hint + "'?)") + "; it takes " + join(keys));
        }
    return j;
}

/// One JSON value as the CLI's text.
std::string valueText(const scene::Param& p, const json& v) {
    if (v.is_string()) return v.get<std::string>();
    if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
    if (v.is_number_float() && !std::isfinite(v.get<double>()))
        throw InputError(p.flag() + ": must be a finite number (got " + v.dump() + ")");
    if (v.is_number()) return v.dump();
    if (v.is_array() && p.kind != scene::Kind::List) {
        std::vector<std::string> parts;
        for (const auto& e : v) {
            if (!e.is_number() && !e.is_string())
                throw InputError(p.flag() + ": a list of numbers or names expected (got " + printable(v.dump()) + ")");
            parts.push_back(valueText(p, e));
        }
        return join(parts, ",");
    }
    throw InputError(p.flag() + ": a number, a name or true/false expected (got " + printable(v.dump()) + ")");
}

struct Server {
    fs::path page, results;  ///< canonical; results "" when there is none
    measurement::GlWorker gl;
    std::atomic<int> queued{0};
    int queueCap = 8;

    /// The values of a request, every one checked as the CLI checks its flag; files relative to the results root.
    scene::Values values(const json& j) const {
        if (!j.is_object()) throw InputError("values: a JSON object {parameter: value} expected");
        scene::Values v;
        for (const auto& item : j.items()) {
            const scene::Param* p = scene::find(item.key());
            if (!p) {
                std::vector<std::string> names;
                for (const scene::Param& q : scene::registry()) names.push_back(q.name);
                const std::string hint = didYouMean(item.key(), names);
                throw InputError("unknown parameter '" + printable(item.key()) + "'" +
                                 (hint.empty() ? "" : " (did you mean '" + hint + "'?)"));
            }
            std::vector<std::string> texts;
            if (p->kind == scene::Kind::List && item.value().is_array())
                for (const auto& e : item.value()) texts.push_back(valueText(*p, e));
            else texts.push_back(valueText(*p, item.value()));
            for (std::string& t : texts) {
                const std::string why = scene::check(*p, t);
                if (!why.empty()) throw InputError(p->flag() + ": " + why);
                if (p->kind == scene::Kind::Path) t = file(t, p->flag());
                v.set(p->name, t);
            }
        }
        return v;
    }

    /// A file a parameter names: under the results root only.
    std::string file(const std::string& rel, const std::string& flag) const {
        if (results.empty())
            throw InputError(flag + ": files are read from the results root, and this server has none (--results)");
        try {
            return confined(results, rel, flag + " '" + printable(rel) + "'").string();
        } catch (const HttpError& e) {
            throw InputError(e.message + " (files are read from the results root)");
        }
    }

    scene::Resolved resolve(const json& body, scene::Purpose purpose = scene::Purpose::Measure) const {
        scene::Resolved r = scene::resolve(values(body.value("values", json::object())), purpose);
        const long px = long(r.setup.width) * r.setup.height * r.setup.supersample * r.setup.supersample;
        if (px > kMaxPixels)
            throw InputError("--size: " + std::to_string(r.setup.width) + "x" + std::to_string(r.setup.height) +
                             " x supersample " + std::to_string(r.setup.supersample) +
                             "^2 is over this server's cap of 1024x1024 pixels");
        if (r.angles.size() > kMaxAngles)
            throw InputError("--incidence: " + std::to_string(r.angles.size()) + " angles, this server takes " +
                             std::to_string(kMaxAngles) + " at most");
        return r;
    }

    /// Runs `job` on the GL thread, or 503 when `queueCap` jobs are queued or running already.
    void onGl(const measurement::GlWorker::Job& job) {
        if (queued.fetch_add(1) >= queueCap) {
            --queued;
            throw HttpError{503, "busy: " + std::to_string(queueCap) + " renders queued already; try again"};
        }
        struct Release {
            std::atomic<int>& n;
            ~Release() { --n; }
        } release{queued};
        gl.run(job);
    }
};

json measureRow(measurement::Session& s, const scene::Resolved& r) {
    json j = measurement::toJson(s.measureOne(r));
    experiments::nameNonFinite(j);
    return j;
}

std::string base64(const std::string& in) {
    static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((in.size() + 2) / 3 * 4);
    for (size_t i = 0; i < in.size(); i += 3) {
        const unsigned n = unsigned(static_cast<unsigned char>(in[i])) << 16 |
                           (i + 1 < in.size() ? unsigned(static_cast<unsigned char>(in[i + 1])) << 8 : 0u) |
                           (i + 2 < in.size() ? unsigned(static_cast<unsigned char>(in[i + 2])) : 0u);
        out += t[(n >> 18) & 63];
        out += t[(n >> 12) & 63];
        out += i + 1 < in.size() ? t[(n >> 6) & 63] : '=';
        out += i + 2 < in.size() ? t[n & 63] : '=';
    }
    return out;
}

/// Grey (1 channel) or colour image as a base64 PNG, its peak white.
std::string pngBase64(const ImageF& img) {
    double peak = 0;
    for (size_t i = 0; i < img.data.size(); ++i)
        if (img.channels == 1 || i % size_t(img.channels) < 3)
            if (std::isfinite(img.data[i])) peak = std::max(peak, double(img.data[i]));
    io::Exposure e;
    e.normalizeTo = peak;
    return base64(io::encodePng(img, e, 1));
}

/// The measured ellipse (chart degrees) as points of a view, top-down pixel coordinates: each point's exitant
/// direction we seen from the camera (the eye) is the ray -we, projected; null below the horizon or far out of
/// the frame.
json ellipsePoints(const json& row, const MirrorChart& chart, const PinholeCamera& cam) {
    auto num = [&](const char* k) { return row.contains(k) && row[k].is_number() ? row[k].get<double>() : NAN; };
    const double cu = num("centroid_u_deg"), cv = num("centroid_v_deg"), a = num("major_deg"), b = num("minor_deg"),
                 phi = num("orientation_deg");
    json pts = json::array();
    if (!std::isfinite(cu + cv + a + b + phi) || a <= 0) return pts;
    const double ca = std::cos(deg2rad(phi)), sa = std::sin(deg2rad(phi));
    for (int k = 0; k < kEllipsePoints; ++k) {
        const double t = 2 * kPi * k / kEllipsePoints;
        const double x = a * std::cos(t), y = b * std::sin(t);
        const dvec3 we = chart.direction(deg2rad(cu + x * ca - y * sa), deg2rad(cv + x * sa + y * ca));
        double nx = 0, ny = 0;
        if (we.z <= 0 || !cam.project(-we, nx, ny) || std::abs(nx) > 3 || std::abs(ny) > 3) {
            pts.push_back(nullptr);
            continue;
        }
        pts.push_back({0.5 * (nx + 1) * cam.width, 0.5 * (1 - ny) * cam.height});
    }
    return pts;
}

/// A view as rendered on the GL thread; the rest (chart coordinates, the ellipse, the PNG) is made on the request's
/// own thread, so that one request's CPU work overlaps the next one's renders.
struct View {
    PinholeCamera camera;
    ImageF image;
};

/// The measurement view of the measured frame (the whole frame, not the crop the measurement analysed).
View renderMeasureView(measurement::Session& s, const scene::Resolved& r, const measurement::Result& res) {
    const PinholeCamera cam = measurement::measurementCamera(r.scene, res.measurement.center, res.measurement.fovDeg,
                                                             r.setup.width, r.setup.height);
    return {cam, s.rendererFor(r).render(r.scene, cam, render::Output::Measure)};
}

/// The photo view (the scene's camera flags).
View renderPhotoView(measurement::Session& s, const scene::Resolved& r) {
    const PinholeCamera cam = scene::viewCamera(r, scene::View::Photo, r.setup.width, r.setup.height);
    return {cam, s.rendererFor(r).render(r.scene, cam, render::Output::Color)};
}

/// The measurement view as grey luminance, the ellipse over it.
json measureViewJson(const View& v, const scene::Resolved& r, const json& row) {
    const int w = v.image.width, h = v.image.height;
    ImageF grey(w, h, 1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) grey.pixel(x, y)[0] = v.image.pixel(x, y)[0];
    return {{"png", pngBase64(grey)},
            {"width", w},
            {"height", h},
            {"ellipse", ellipsePoints(row, r.scene.light.chart(), v.camera)}};
}

/// The photo view, the ellipse over it.
json photoViewJson(const View& v, const scene::Resolved& r, const json& row) {
    return {{"png", pngBase64(v.image)},
            {"width", v.image.width},
            {"height", v.image.height},
            {"ellipse", ellipsePoints(row, r.scene.light.chart(), v.camera)}};
}

std::vector<std::string> resultFolders(const fs::path& root) {
    std::vector<std::string> out;
    if (root.empty()) return out;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
        if (it.depth() >= 2) it.disable_recursion_pending();
        if (it->is_directory(ec) && !it->is_symlink(ec) && fs::exists(it->path() / "results.jsonl", ec))
            out.push_back(fs::relative(it->path(), root).string());
        if (out.size() >= 500) break;
    }
    std::sort(out.begin(), out.end());
    return out;
}

std::vector<std::string> brdfFiles(const fs::path& root) {
    std::vector<std::string> out;
    if (root.empty()) return out;
    std::error_code ec;
    for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
        if (it.depth() >= 3) it.disable_recursion_pending();
        const std::string e = it->path().extension().string();
        if (it->is_regular_file(ec) && !it->is_symlink(ec) && (e == ".brdf" || e == ".binary" || e == ".bsdf"))
            out.push_back(fs::relative(it->path(), root).string());
        if (out.size() >= 500) break;
    }
    std::sort(out.begin(), out.end());
    return out;
}

void answer(httplib::Response& res, int status, const std::string& line) {
    res.status = status;
    res.set_content(line + "\n", "text/plain; charset=utf-8");
}

/// A handler that answers its exceptions with one line: HttpError its status, InputError 400, other 500.
httplib::Server::Handler guarded(std::function<void(const httplib::Request&, httplib::Response&)> fn) {
    return [fn](const httplib::Request& req, httplib::Response& res) {
        const auto t0 = std::chrono::steady_clock::now();
        struct Log {  // --log: one line per request on stderr, when the answer is sent
            const httplib::Request& req;
            const httplib::Response& res;
            std::chrono::steady_clock::time_point t0;
            ~Log() {
                if (!g_log) return;
                const double ms =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
                std::fprintf(stderr, "%s %s %d %.1f ms\n", req.method.c_str(), printable(req.path).c_str(),
                             res.status < 0 ? 200 : res.status, ms);
            }
        } log{req, res, t0};
        try {
            fn(req, res);
        } catch (const HttpError& e) {
            answer(res, e.status, "hilite: " + e.message);
        } catch (const InputError& e) {
            answer(res, 400, "hilite: " + std::string(e.what()));
        } catch (const SystemError& e) {
            answer(res, 500, "hilite: " + std::string(e.what()));
        } catch (const std::exception& e) {
            answer(res, 500, "hilite: internal error: " + std::string(e.what()));
        }
        std::string& body = res.body;  // one line: a multi-line message is joined
        if (res.status >= 400)
            for (size_t i = 0; i + 1 < body.size(); ++i)
                if (body[i] == '\n' || body[i] == '\r') body[i] = ' ';
    };
}

void sendJson(httplib::Response& res, const json& j) {
    res.set_content(j.dump(-1, ' ', false, json::error_handler_t::replace), kJson);
}

fs::path findPage() {
    std::string tried;
    for (const SharePlace& place : sharePlaces()) {
        std::error_code ec;
        const fs::path dir = fs::path(place.dir) / kPageDir;
        if (fs::exists(dir / "index.html", ec)) return fs::canonical(dir, ec);
        tried += (tried.empty() ? "" : ", ") + dir.string() + " (" + place.why + ")";
    }
    throw SystemError("serve: the page (serve/index.html) is not found; looked in " + tried);
}

void addRoutes(httplib::Server& http, Server& s) {
    http.Get("/api/registry", guarded([](const httplib::Request&, httplib::Response& res) {
                 sendJson(res, {{"parameters", registryJson()}});
             }));
    http.Post("/api/resolve", guarded([&s](const httplib::Request& req, httplib::Response& res) {
                  const scene::Resolved r = s.resolve(parseBody(req, {"values"}));
                  sendJson(res, {{"angles", r.angles},
                                 {"size", {r.setup.width, r.setup.height}},
                                 {"effects", render::activeEffects(r.scene)},
                                 {"columns", scene::parameterColumns(r)}});
              }));
    http.Post("/api/match", guarded([&s](const httplib::Request& req, httplib::Response& res) {
                  // The width of `values`' model whose half-maximum radius at normal incidence is the target's.
                  const json body = parseBody(req, {"values", "target"});
                  const scene::Resolved target = s.resolve({{"values", body.value("target", json::object())}});
                  const scene::Resolved r = s.resolve(body);
                  if (target.scene.brdfFile || r.scene.brdfFile || target.scene.brdf.isMeasured() ||
                      r.scene.brdf.isMeasured())
                      throw InputError("match: analytic models only (a .brdf file or a measured table has no width)");
                  render::Scene t = target.scene;
                  t.light.incidenceDeg = 0;
                  const double threshold = r.setup.options.threshold;
                  double major = 0, value = 0;
                  s.onGl([&](measurement::Session&) {  // CPU work, one at a time like the renders
                      major = rad2deg(measurement::twinHalfWidth(t, threshold));
                      value = experiments::matchedWidth(r.scene, major, threshold);
                  });
                  sendJson(res, {{"parameter", brdf::usesExponent(r.scene.brdf.model) ? "exponent" : "roughness"},
                                 {"value", value},
                                 {"target_major_deg", major}});
              }));
    http.Post("/api/measure", guarded([&s](const httplib::Request& req, httplib::Response& res) {
                  scene::Resolved r = s.resolve(parseBody(req, {"values"}));
                  json rows = json::array();
                  s.onGl([&](measurement::Session& session) {
                      for (double angle : r.angles) {
                          r.scene.light.incidenceDeg = angle;
                          rows.push_back(measureRow(session, r));
                      }
                  });
                  sendJson(res, {{"rows", rows}});
              }));
    http.Post("/api/render", guarded([&s](const httplib::Request& req, httplib::Response& res) {
                  const json body = parseBody(req, {"values", "views"});
                  const scene::Resolved r = s.resolve(body);
                  if (r.angles.size() != 1)
                      throw InputError(r.values.where("incidence") + ": render takes one angle (got '" +
                                       r.values.text("incidence") + "')");
                  std::vector<std::string> views = {"photo", "measure"};
                  if (body.contains("views")) {
                      if (!body["views"].is_array()) throw InputError("views: a list of photo, measure expected");
                      views.clear();
                      for (const auto& v : body["views"]) {
                          if (!v.is_string() || (v != "photo" && v != "measure"))
                              throw InputError("views: photo or measure (got " + printable(v.dump()) + ")");
                          views.push_back(v.get<std::string>());
                      }
                  }
                  json out;
                  std::optional<measurement::Result> result;
                  std::vector<View> rendered;
                  using Clock = std::chrono::steady_clock;
                  Clock::time_point t0, t1, t2;
                  s.onGl([&](measurement::Session& session) {
                      t0 = Clock::now();
                      result = session.measureOne(r);
                      t1 = Clock::now();
                      for (const std::string& v : views)
                          rendered.push_back(v == "photo" ? renderPhotoView(session, r)
                                                          : renderMeasureView(session, r, *result));
                      t2 = Clock::now();
                  });
                  json row = measurement::toJson(*result);
                  experiments::nameNonFinite(row);
                  out["row"] = row;
                  for (size_t i = 0; i < views.size(); ++i)
                      out[views[i]] = views[i] == "photo" ? photoViewJson(rendered[i], r, row)
                                                          : measureViewJson(rendered[i], r, row);
                  if (g_log) {
                      auto ms = [](Clock::time_point a, Clock::time_point b) {
                          return std::chrono::duration<double, std::milli>(b - a).count();
                      };
                      std::fprintf(stderr,
                                   "  render: measured in %.1f ms, views rendered in %.1f ms, encoded in %.1f ms\n",
                                   ms(t0, t1), ms(t1, t2), ms(t2, Clock::now()));
                  }
                  sendJson(res, out);
              }));
    http.Post(
        "/api/slice", guarded([&s](const httplib::Request& req, httplib::Response& res) {
            const json body = parseBody(req, {"curves", "step"});
            const double step = body.value("step", 1.0);
            if (!(step >= 0.25 && step <= 10))
                throw InputError("--step: in [0.25, 10] here (got " + body["step"].dump() + ")");
            if (!body.contains("curves") || !body["curves"].is_array() || body["curves"].empty() ||
                body["curves"].size() > 4)
                throw InputError("curves: a list of 1 to 4 {label, values} expected");
            std::vector<experiments::SliceCurve> curves;
            for (const auto& c : body["curves"]) {
                if (!c.is_object()) throw InputError("curves: a list of 1 to 4 {label, values} expected");
                for (const auto& item : c.items())
                    if (item.key() != "label" && item.key() != "values")
                        throw InputError("curves: unknown key '" + printable(item.key()) + "'; it takes label, values");
                const std::string label = c.value("label", std::string("curve"));
                scene::Resolved r = s.resolve({{"values", c.value("values", json::object())}}, scene::Purpose::Brdf);
                if (r.angles.size() > 4) throw InputError("--incidence: at most 4 angles in a slice here");
                curves.push_back({printable(label), r});
            }
            std::vector<experiments::SlicePoint> points;
            s.onGl([&](measurement::Session&) {  // CPU work (a measured table read), one at a time
                points = experiments::brdfSlices(curves, curves.front().scene.angles, step);
            });
            json out = json::array();
            for (const auto& p : points) out.push_back(experiments::toJson(p));
            sendJson(res, {{"points", out}});
        }));
    http.Post("/api/explain", guarded([&s](const httplib::Request& req, httplib::Response& res) {
                  const scene::Resolved r = s.resolve(parseBody(req, {"values"}));
                  std::ostringstream toml;
                  printScene(r, toml);
                  sendJson(res, {{"effects", render::activeEffects(r.scene)}, {"scene_toml", toml.str()}});
              }));
    http.Get("/api/results", guarded([&s](const httplib::Request&, httplib::Response& res) {
                 sendJson(res, {{"folders", resultFolders(s.results)}});
             }));
    http.Get("/api/files", guarded([&s](const httplib::Request&, httplib::Response& res) {
                 sendJson(res, {{"files", brdfFiles(s.results)}});
             }));
    http.Get(R"(/api/results/(.+))", guarded([&s](const httplib::Request& req, httplib::Response& res) {
                 if (s.results.empty()) throw HttpError{404, "this server has no results root"};
                 const fs::path dir = confined(s.results, req.matches[1].str(), "result folder");
                 std::error_code ec;
                 if (!fs::exists(dir / "results.jsonl", ec)) throw HttpError{404, "result folder: no results.jsonl"};
                 const fs::path rowsFile =
                     confined(s.results, fs::relative(dir / "results.jsonl", s.results).string(), "results.jsonl");
                 std::vector<json> rows = experiments::readRows(rowsFile.string());
                 const bool cut = rows.size() > kMaxRows;
                 if (cut) rows.resize(kMaxRows);
                 std::vector<std::string> pictures;
                 for (const auto& e : fs::directory_iterator(dir, ec))
                     if (e.path().extension() == ".png" && !e.is_symlink(ec))
                         pictures.push_back(e.path().filename().string());
                 std::sort(pictures.begin(), pictures.end());
                 sendJson(res, {{"folder", fs::relative(dir, s.results).string()},
                                {"rows", rows},
                                {"rows_cut", cut},
                                {"pictures", pictures}});
             }));
    http.Get(R"(/results/(.*))", guarded([&s](const httplib::Request& req, httplib::Response& res) {
                 if (s.results.empty()) throw HttpError{404, "this server has no results root"};
                 const fs::path p = confined(s.results, req.matches[1].str(), "file");
                 res.set_content(readFile(p), contentType(p, false));
             }));
    http.Get(R"(/(.*))", guarded([&s](const httplib::Request& req, httplib::Response& res) {
                 std::string rel = req.matches[1].str();
                 if (rel.empty()) rel = "index.html";
                 if (rel.rfind("api/", 0) == 0) throw HttpError{404, "no API endpoint GET /" + printable(rel)};
                 const fs::path p = confined(s.page, rel, "file");
                 res.set_content(readFile(p), contentType(p, true));
             }));
}

int runServe(const ServeFlags& f) {
    if (f.port < 0 || f.port > 65535) throw InputError("--port: in [0, 65535] (got " + std::to_string(f.port) + ")");
    if (f.queue < 1 || f.queue > 1024) throw InputError("--queue: in [1, 1024] (got " + std::to_string(f.queue) + ")");
    Server s;
    s.queueCap = f.queue;
    g_log = f.log;
    s.page = findPage();
    std::error_code ec;
    if (!f.results.empty() && fs::is_directory(f.results, ec)) s.results = fs::canonical(f.results, ec);
    else if (f.results != kDefaultResults)
        throw InputError("--results: '" + printable(f.results) + "' is not a folder");

    httplib::Server http;
    http.new_task_queue = [] { return new httplib::ThreadPool(kHttpThreads); };
    http.set_payload_max_length(kMaxBody);
    http.set_tcp_nodelay(true);  // Nagle's algorithm held each answer's last segment ~40 ms
    http.set_read_timeout(10, 0);
    http.set_write_timeout(10, 0);
    http.set_keep_alive_max_count(100);
    http.set_default_headers({{"X-Content-Type-Options", "nosniff"},
                              {"Content-Security-Policy", "default-src 'self'; img-src 'self' data: blob:"},
                              {"Cache-Control", "no-store"}});
    http.set_error_handler([](const httplib::Request&, httplib::Response& res) {
        if (!res.body.empty()) return;
        const char* what = res.status == 413   ? "request body over the server's cap of 64 KiB"
                           : res.status == 404 ? "not found"
                                               : "request refused";
        answer(res, res.status, std::string("hilite: ") + what);
    });
    // Requests naming another host are refused: a web page elsewhere could otherwise reach this server through a
    // name it points at 127.0.0.1 (DNS rebinding) and read the results root.
    http.set_pre_routing_handler([host = f.host](const httplib::Request& req, httplib::Response& res) {
        std::string h = req.get_header_value("Host");
        const size_t colon = h.rfind(':');
        if (colon != std::string::npos && h.find(']', colon) == std::string::npos) h.resize(colon);
        if (h == host || h == "localhost" || h == "127.0.0.1" || h == "[::1]" || host == "0.0.0.0" || host == "::")
            return httplib::Server::HandlerResponse::Unhandled;
        answer(res, 403, "hilite: Host '" + printable(h) + "' refused (this server answers to " + host + ")");
        return httplib::Server::HandlerResponse::Handled;
    });
    addRoutes(http, s);
    // cpp-httplib listens with a backlog of 5: under load (llvmpipe on every core) a burst of connections
    // overflowed it and clients were reset. The socket is kept here and listened on again with the system's cap.
    int socket = -1;
    http.set_socket_options([&socket](int fd) {
        const int yes = 1;
        ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
        socket = fd;
    });
    int port = f.port;
    if (port == 0) port = http.bind_to_any_port(f.host);
    else if (!http.bind_to_port(f.host, port)) port = -1;
    if (port < 0)
        throw SystemError("serve: cannot listen on " + f.host + ":" + std::to_string(f.port) +
                          " (in use, or not an address of this machine)");
    if (socket >= 0) ::listen(socket, SOMAXCONN);
    std::cout << "serving http://" << f.host << ":" << port << "/" << std::endl;
    std::cout << "page " << s.page.string() << ", results root "
              << (s.results.empty() ? std::string("(none)") : s.results.string()) << std::endl;
    const bool ok = http.listen_after_bind();
    s.gl.stop();
    if (!ok) throw SystemError("serve: the server stopped");
    return 0;
}

}  // namespace

Action addServe(CLI::App& app) {
    auto f = std::make_shared<ServeFlags>();
    app.add_option("--host", f->host,
                   "address to listen on; the default is loopback only (another address exposes the server to the "
                   "network)")
        ->capture_default_str()
        ->check(nonEmpty());
    app.add_option("--port", f->port, "port to listen on (0: a free one, printed)")->capture_default_str();
    app.add_option("--results", f->results,
                   "results root: the result folders the page browses and the .brdf/MERL/RGL files it reads")
        ->capture_default_str()
        ->check(nonEmpty());
    app.add_option("--queue", f->queue, "renders queued or running at most; more are answered 503")
        ->capture_default_str();
    app.add_flag("--log", f->log, "one line per request on stderr: method, path, status, milliseconds");
    app.footer("Example: hilite serve --results results   (then open http://127.0.0.1:8765/)");
    return [f] { return runServe(*f); };
}

}  // namespace hilite::cli
