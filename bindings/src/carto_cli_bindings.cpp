// rockhatch.carto, the command line: the rockhatch option table, its help and style
// listings, and its progress bar.
#include "carto/cli.hpp"
#include "carto/progress.hpp"
#include "carto/styles.hpp"
#include "carto_bindings.hpp"

namespace rhpy {

using namespace carto;

// The command line: parse_command_line, the help texts, ProgressBar.
void add_cli_bindings(py::module_& m) {
    py::class_<CommandLine>(m, "CommandLine")
        .def_readonly("options", &CommandLine::options)
        .def_readonly("script", &CommandLine::script)
        .def_readonly("quiet", &CommandLine::quiet)
        .def_readonly("list_styles", &CommandLine::list_styles)
        .def_readonly("help", &CommandLine::help);
    m.def("parse_command_line", &parse_command_line, py::arg("args"), "the rockhatch option table");
    py::class_<UpdateCommandLine>(m, "UpdateCommandLine")
        .def_readonly("command", &UpdateCommandLine::command)
        .def_readonly("reset", &UpdateCommandLine::reset)
        .def_readonly("faces", &UpdateCommandLine::faces);
    m.def("parse_update_command_line", &parse_update_command_line, py::arg("args"),
          "rockhatch update's command line: the rockhatch option table, --reset and --face ID");
    m.def("update_help_text", &update_help_text);
    py::class_<ProgressBar>(m, "ProgressBar",
                            "The progress bar of the rockhatch command on standard error; as a progress callback it "
                            "never cancels")
        .def(py::init<bool, std::string>(), py::arg("on") = false, py::arg("prefix") = "")
        .def("__call__", &ProgressBar::operator(), py::arg("fraction"), py::arg("stage"))
        .def("finish", &ProgressBar::finish, "ends an unfinished bar line");
    m.def("help_text", &help_text);
    m.def("styles_text", &styles_text);
    m.def(
        "params_text",
        [](const py::iterable& params, int indent) {
            std::vector<StyleParam> ps;
            for (const py::handle& h : params) {
                if (py::isinstance<StyleParam>(h)) {
                    ps.push_back(h.cast<StyleParam>());
                    continue;
                }
                const auto t = h.cast<py::sequence>();
                ps.push_back({t[0].cast<std::string>(), t[1].cast<double>(), t[2].cast<std::string>(),
                              t.size() > 3 ? t[3].cast<std::string>() : std::string()});
            }
            return params_text(ps, indent);
        },
        py::arg("params"), py::arg("indent") = 4,
        "the parameter lines of --list-styles for a table of StyleParam or (name, default, unit, help) tuples "
        "(a style script's header is made from its PARAMS)");
}

}  // namespace rhpy
