#pragma once
// A scene as given (parameter values as text, each with where it came from) and scene::resolve(), the
// one place where the parameters are read, checked against each other and turned into the scene that is
// rendered and the settings it is measured with. Every error names the flag or the file:line: key.

#include "hilite/gl/backend.hpp"
#include "hilite/render/scene.hpp"
#include "hilite/scene/registry.hpp"
#include "hilite/scene/setup.hpp"

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace hilite::scene {

/// Parameter values by registry name, as text, each with its origin. Later set() calls win; a List
/// parameter (param) accumulates its assignments in order.
class Values {
public:
    struct Value {
        std::string text;
        std::string
            origin;  ///< "" = the command line (messages name the flag), else "scene.toml:4: material.roughness"
    };
    /// Sets a registered parameter (InputError for an unknown name). The text is not checked here.
    void set(const std::string& name, const std::string& text, const std::string& origin = "");
    /// A command's own default for a parameter (render: size 512; brdf albedo: incidence 0:85:5).
    void setDefault(const std::string& name, const std::string& text);
    /// Everything `later` sets, over this.
    void merge(const Values& later);
    bool given(const std::string& name) const { return m_values.count(name) > 0; }
    /// The given text, else the command's default, else the registry's.
    std::string text(const std::string& name) const;
    /// A List parameter's assignments in order.
    const std::vector<Value>& list(const std::string& name) const;
    /// Where a value came from, for messages: its origin, else the flag ("--roughness").
    std::string where(const std::string& name) const;
    const std::map<std::string, Value>& given() const { return m_values; }
    const std::map<std::string, std::vector<Value>>& lists() const { return m_lists; }

private:
    std::map<std::string, Value> m_values;
    std::map<std::string, std::vector<Value>> m_lists;
    std::map<std::string, std::string> m_defaults;
};

enum class View { Measure, Photo };
/// --view's spellings.
inline constexpr Named<View> kViews[] = {{View::Measure, "measure"}, {View::Photo, "photo"}};
inline const char* toString(View v) { return nameIn(kViews, v); }

/// What the values resolve to: the scene as rendered, and how it is measured.
struct Resolved {
    render::Scene scene;         ///< light.incidenceDeg: the first of `angles`
    std::vector<double> angles;  ///< --incidence: one, a list or a range
    MeasureSetup setup;
    double tolerance = 0;                ///< > 0: choose the settings that reach this aspect error
    bool reference = false;              ///< measure with the CPU double reference
    View view = View::Measure;           ///< render only: a measurement always uses the measurement view
    double fovDeg = 0;                   ///< 0: --fov auto, the view's default (render) or automatic framing (measure)
    std::optional<double> elevationDeg;  ///< photo view; none: --elevation auto, 90 - incidence
    std::string backend;                 ///< as given ("" = $HILITE_GL_BACKEND or auto), checked
    int gpu = -1;  ///< --gpu: the EGL device (egl-device, auto), checked against the devices; -1 unset
    double shaderTimeoutS = 10;
    int spectralStepNm = 5;
    Values values;  ///< what was resolved, as given
};

/// Which command reads the values: the checks that differ (render's wider field of view; brdf's
/// integrable roughness) and nothing else.
enum class Purpose { Measure, Render, Brdf };

/// Reads, checks and combines every parameter. Throws InputError naming the flag (or file:line: key)
/// and the allowed values. Warnings (clamped roughness, a mirror) go to stderr once per process.
Resolved resolve(const Values& values, Purpose purpose = Purpose::Measure);

/// The Fresnel term `hilite brdf fresnel` and `strip` (and hilite.brdf.fresnel) evaluate: `spectral` sets
/// --fresnel spectral (measured spectra: copper, gold only; a conflicting --fresnel is refused); the term must
/// be one (a material or a --fresnel other than none). InputError naming the flag otherwise.
brdf::Params resolveFresnel(Values values, bool spectral);

/// Switches the energy terms (--multiscatter, --diffuse coupled) off, for a search that sets the lobe's
/// roughness or exponent directly: their tables belong to the parameters they were integrated for, and their
/// broad lobes do not set the highlight's width, so the search matches the lobe alone (the value found then
/// resolves with its own tables).
void dropEnergyTerms(brdf::Params& p);

/// The camera of the resolved view at the scene's incidence.
PinholeCamera viewCamera(const Resolved& r, View view, int width, int height);
/// The GL backend named by `name` (--gl-backend: "" = $HILITE_GL_BACKEND, else auto); InputError if unknown.
gl::Backend backendOf(const std::string& name);
/// The GL backend of the resolved values.
inline gl::Backend backendOf(const Resolved& r) { return backendOf(r.backend); }
/// The row columns of the resolved scene: every registry parameter that applies, as rendered.
nlohmann::json parameterColumns(const Resolved& r);

/// Largest tolerance range: below 1e-5 the double reference itself cannot confirm it; above 0.1 the
/// aspect says little.
constexpr double kMinTolerance = 1e-5, kMaxTolerance = 0.1;

}  // namespace hilite::scene
