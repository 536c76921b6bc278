#include "experiments/strip.hpp"

#include "hilite/brdf/evaluate.hpp"
#include "hilite/core/image.hpp"
#include "io/image_io.hpp"
#include "io/label.hpp"

#include <algorithm>
#include <cmath>

namespace hilite::experiments {

namespace {

dvec3 fresnelAt(const brdf::Params& p, double thetaDeg) {
    double c, s;
    cosSinDeg(thetaDeg, c, s);
    return brdf::fresnel(p, c);
}

}  // namespace

void writeFresnelStrip(const brdf::Params& p, int width, int height, const std::string& path,
                       const std::string& label) {
    const int scale = 1, band = label.empty() ? 0 : 2 * io::textHeight(scale) + 6;
    ImageF img(width, height + band, 3);
    for (int x = 0; x < width; ++x) {  // normal incidence on the left, grazing on the right
        const dvec3 F = fresnelAt(p, 90.0 * (x + 0.5) / width);
        for (int y = band; y < band + height; ++y)
            for (int ch = 0; ch < 3; ++ch) img.pixel(x, y)[ch] = float(F[ch]);
    }
    if (band > 0) {
        for (int t = 0; t <= 90; t += 15) {
            const int x = std::min(width - 1, int(std::lround(double(t) / 90.0 * width)));
            for (int y = band - 4; y < band; ++y) img.pixel(x, y)[0] = img.pixel(x, y)[1] = img.pixel(x, y)[2] = 1.0f;
            const std::string tick = std::to_string(t) + (t == 90 ? " deg" : "");
            io::drawText(img, std::clamp(x - io::textWidth(tick, scale) / 2, 0, width - io::textWidth(tick, scale)),
                         height + 5, tick, scale);
        }
        io::drawText(img, 2, height + 5 + io::textHeight(scale), label + ": F(theta), theta_i 0 (left) to 90 (right)",
                     scale);
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
