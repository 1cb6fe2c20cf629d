// rockhatch.tex, geometry and curves: Point, BBox, Region, the labelled curves arrangements
// return, and the curve utilities of table 3.6.
#include <sstream>

#include <pybind11/operators.h>

#include "tex_bindings.hpp"

namespace rhpy {
namespace {

using namespace tex;

std::string repr(const Point& p) {
    std::ostringstream s;
    s.precision(17);
    s << "Point(" << p.x << ", " << p.y << ")";
    return s.str();
}

Curves polyline(const std::vector<Point>& pts, bool closed) { return Polyline(pts, closed); }

}  // namespace

// Geometry: pi, Point and its vector algebra, BBox, Region.
void add_geometry_bindings(py::module_& m) {
    m.attr("pi") = tex::pi;

    py::class_<Point>(m, "Point", "A point or vector of the plane, with + - * / and ==")
        .def(py::init<>())
        .def(py::init<double, double>(), py::arg("x"), py::arg("y"))
        .def(py::init([](const py::tuple& t) {
            if (t.size() != 2) throw py::type_error("Point: a tuple of two numbers is needed");
            return Point(t[0].cast<double>(), t[1].cast<double>());
        }))
        .def_readwrite("x", &Point::x)
        .def_readwrite("y", &Point::y)
        .def(py::self + py::self)
        .def(py::self - py::self)
        .def(py::self * double())
        .def(double() * py::self)
        .def(py::self / double())
        .def(-py::self)
        .def(py::self == py::self)
        .def(py::self != py::self)
        .def("__hash__", [](const Point& p) { return py::hash(py::make_tuple(p.x, p.y)); })
        .def("__iter__", [](const Point& p) { return py::iter(py::make_tuple(p.x, p.y)); })
        .def("__repr__", &repr)
        .def(py::pickle([](const Point& p) { return py::make_tuple(p.x, p.y); },
                        [](const py::tuple& t) { return Point(t[0].cast<double>(), t[1].cast<double>()); }));
    py::implicitly_convertible<py::tuple, Point>();
    m.def("dot", &dot);
    m.def("cross", &cross);
    m.def("norm", &norm, "length of a vector (std::hypot)");
    m.def("distance", &distance, "distance between two points (std::hypot)");
    m.def("signed_area", &signed_area, "signed area of a ring (positive when counter-clockwise)");

    py::class_<BBox>(m, "BBox", "Axis-aligned box")
        .def(py::init<>())
        .def(py::init([](double x0, double y0, double x1, double y1) { return BBox{x0, y0, x1, y1}; }),
             py::arg("xmin"), py::arg("ymin"), py::arg("xmax"), py::arg("ymax"))
        .def_readwrite("xmin", &BBox::xmin)
        .def_readwrite("ymin", &BBox::ymin)
        .def_readwrite("xmax", &BBox::xmax)
        .def_readwrite("ymax", &BBox::ymax)
        .def("empty", &BBox::empty)
        .def("width", &BBox::width)
        .def("height", &BBox::height)
        .def("center", &BBox::center)
        .def("add", py::overload_cast<const Point&>(&BBox::add))
        .def("add", py::overload_cast<const BBox&>(&BBox::add))
        .def("contains", &BBox::contains)
        .def("intersects", &BBox::intersects)
        .def("expanded", &BBox::expanded)
        .def("__repr__", [](const BBox& b) {
            std::ostringstream s;
            s << "BBox(" << b.xmin << ", " << b.ymin << ", " << b.xmax << ", " << b.ymax << ")";
            return s.str();
        });

    py::class_<Region>(m, "Region", "A polygon with holes: the domain an arrangement is evaluated on")
        .def(py::init<std::vector<Point>, std::vector<std::vector<Point>>, const std::string&>(), py::arg("outer"),
             py::arg("holes") = std::vector<std::vector<Point>>{}, py::arg("op") = "Region")
        .def_static("rectangle", &Region::rectangle, py::arg("xmin"), py::arg("ymin"), py::arg("xmax"), py::arg("ymax"))
        .def_property_readonly("outer", &Region::outer)
        .def_property_readonly("holes", &Region::holes)
        .def("bbox", &Region::bbox)
        .def("area", &Region::area)
        .def("area_within", &Region::area_within, py::arg("convex"),
             "the area of the region inside a convex region (its outer ring)")
        .def("contains", &Region::contains, "even-odd test; points on a ring count as inside")
        .def("boundary", &Region::boundary,
             "the boundary as curves, inside on the left: its labelled edges when it has them, else its rings")
        .def("with_edges", &Region::with_edges, py::arg("edges"),
             "the same region with its boundary given as labelled curves (a face's edges), which partitions "
             "cropped to it with CROP_ADD_BOUNDARY keep on their outline")
        .def("has_edges", &Region::has_edges);
}

// Curves: Curve, LabeledPoint, Curves, and the table 3.6 utilities.
void add_curve_bindings(py::module_& m) {
    py::class_<Curve>(m, "Curve", "A labelled polyline")
        .def(py::init([](std::vector<Point> pts, bool closed, std::vector<std::string> labels) {
                 Curve c;
                 c.points = std::move(pts);
                 c.closed = closed;
                 c.labels = Labels::from_names(labels);
                 return c;
             }),
             py::arg("points"), py::arg("closed") = false, py::arg("labels") = std::vector<std::string>{})
        .def_readwrite("points", &Curve::points)
        .def_readwrite("closed", &Curve::closed)
        .def_property(
            "labels", [](const Curve& c) { return names(c.labels); },
            [](Curve& c, const std::vector<std::string>& l) { c.labels = Labels::from_names(l); })
        .def_property(
            "left", [](const Curve& c) { return names(c.left); },
            [](Curve& c, const std::vector<std::string>& l) { c.left = Labels::from_names(l); })
        .def_property(
            "right", [](const Curve& c) { return names(c.right); },
            [](Curve& c, const std::vector<std::string>& l) { c.right = Labels::from_names(l); });

    py::class_<LabeledPoint>(m, "LabeledPoint", "A labelled point carried along with curves (e.g. start, end)")
        .def_readonly("point", &LabeledPoint::point)
        .def_property_readonly("labels", [](const LabeledPoint& p) { return names(p.labels); });

    py::class_<Curves>(m, "Curves", "What arrangements return and mappers produce: labelled curves and points")
        .def(py::init<>())
        .def_property(
            "curves", [](const Curves& c) { return c.curves; },
            [](Curves& c, std::vector<Curve> v) { c.curves = std::move(v); })
        .def_property_readonly("points", [](const Curves& c) { return c.points; })
        .def_readwrite("origin", &Curves::origin)
        .def("__len__", &Curves::size)
        .def("empty", &Curves::empty)
        .def("bbox", &Curves::bbox)
        .def("append", [](Curves& c, const Curves& o) { c.append(o); }, "appends the curves of another set in place")
        .def("add_point", [](Curves& c, const Point& p, const std::vector<std::string>& labels) {
            c.points.push_back({p, Labels::from_names(labels)});
        })
        .def("__repr__", [](const Curves& c) {
            return "Curves(" + std::to_string(c.curves.size()) + " curves, " + std::to_string(c.points.size()) +
                   " labelled points)";
        });

    // Table 3.6 utilities.
    m.def("Nothing", &Nothing, "an empty set of curves");
    m.def("Append", &Append, py::arg("c1"), py::arg("c2"));
    m.def("BBoxWidth", [](const Curves& c) { return BBoxWidth(c); });
    m.def("BBoxHeight", [](const Curves& c) { return BBoxHeight(c); });
    m.def("BBoxCenter", [](const Curves& c) { return BBoxCenter(c); });
    m.def("Scale", py::overload_cast<const Curves&, double>(&Scale), py::arg("c"), py::arg("s"),
          "scales about the centre of the bounding box");
    m.def("Scale", py::overload_cast<const Curves&, double, double>(&Scale), py::arg("c"), py::arg("sx"),
          py::arg("sy"));
    m.def("Rotate", &Rotate, py::arg("c"), py::arg("a"), "rotates by a radians about the centre of the bounding box");
    m.def("Translate", &Translate, py::arg("c"), py::arg("v"));
    m.def("MatchPoint", &MatchPoint, py::arg("c"), py::arg("s"), py::arg("t"), "translates c by t - s");
    m.def("MatchPoints", &MatchPoints, py::arg("c"), py::arg("s1"), py::arg("s2"), py::arg("t1"), py::arg("t2"),
          "the similarity sending s1 to t1 and s2 to t2");
    m.def("PointLabeled", &PointLabeled, py::arg("c"), py::arg("label"));
    m.def("CurveLabeled", &CurveLabeled, py::arg("c"), py::arg("label"));
    m.def("Labelled", &Labelled, py::arg("c"), py::arg("label"), "the curves with one more label");
    m.def("Polyline", &polyline, py::arg("points"), py::arg("closed") = false, "one polyline as curves");
}

}  // namespace rhpy
