// Darts turned by a control field (see gallery_fields.hpp).
#include "gallery_fields.hpp"

#include "gallery.hpp"

namespace gallery::fields {
using namespace tex;

Field towards(const Point& target) {
    return Angle(VectorField([target](const Point& p) { return target - p; }));
}

ControlledFaceMapper turned_element(Curves element) {
    return ControlledFaceMapper("turned_element", 1, [element](const std::vector<Field>& f) {
        const Field angle = f[0];
        return FaceMapper([element, angle](const Face& face) {
            const Point c = Centroid(face);
            const Curves turned = Rotate(element, angle(c));
            return MatchPoint(turned, BBoxCenter(turned), c);
        });
    });
}

ControlledArrangement turned_elements(Curves element, double density) {
    const ControlledFaceMapper mapper = turned_element(std::move(element));
    return ControlledArrangement("turned_elements", 1, [mapper, density](const std::vector<Field>& f) {
        return MapToFaces(mapper(f), UniformPartition(IrregularProperties(density), KEEP_OUTSIDE));
    });
}

Arrangement darts(const std::string& dir) {
    const Field to_centre = towards(Point{kSize / 2, kSize / 2});
    return turned_elements(gallery::element(dir + "/dart.svg"), kDartDensity)(to_centre);
}

}  // namespace gallery::fields
