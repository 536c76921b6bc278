#include "experiments/strip.hpp"

#include "brdf/evaluate.hpp"
#include "core/image.hpp"
#include "io/image_io.hpp"

namespace hilite::experiments {

namespace {

dvec3 fresnelAt(const brdf::Params& p, double thetaDeg) {
    double c, s;
    cosSinDeg(thetaDeg, c, s);
    return brdf::fresnel(p, c);
}

}  // namespace

void writeFresnelStrip(const brdf::Params& p, int width, int height, const std::string& path) {
    ImageF img(width, height, 3);
    for (int x = 0; x < width; ++x) {  // normal incidence on the left, grazing on the right
        const dvec3 F = fresnelAt(p, 90.0 * (x + 0.5) / width);
        for (int y = 0; y < height; ++y)
            for (int ch = 0; ch < 3; ++ch) img.pixel(x, y)[ch] = float(F[ch]);
    }
    io::writePng(path, img, io::Exposure{});
}

StripStats fresnelStats(const brdf::Params& p) {
    StripStats s;
    s.normal = fresnelAt(p, 0.0);
    s.grazing89 = fresnelAt(p, 89.0);
    s.redMin = s.normal.x;
    for (int i = 0; i <= 9000; ++i) {  // 0.01 degree steps
        const double t = 0.01 * i;
        const double r = fresnelAt(p, t).x;
        if (r < s.redMin) s.redMin = r, s.redMinThetaDeg = t;
    }
    return s;
}

}  // namespace hilite::experiments
