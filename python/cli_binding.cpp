// dqskin.bake, diff, lint and report: the command line's own commands run in-process, their flags as
// keyword arguments, their machine-readable output returned as dicts. Running the commands themselves
// (app/, through run_cli) rather than a second binding of each option keeps one parser, one set of
// defaults and one set of messages: what the CLI accepts and refuses, the module does, word for word.
#include "interruptible.hpp"

#include "commands.hpp"
#include "exit_codes.hpp"
#include "guarded_run.hpp"
#include "interrupt.hpp"

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace dqskin::python {

namespace py = pybind11;

namespace {

struct Captured {
  int status = 0;
  bool output_error = false;  // the command stopped on a file it could not write
  std::string out, err;
};

// Runs `argv` through run_cli with its standard streams captured and Python's cancel flag as its interrupt.
// One command at a time: the streams and the interrupt flag are the process's.
Captured run_captured(const std::vector<std::string>& argv) {
  static std::mutex one_at_a_time;
  Captured c;
  run_interruptible([&](const std::atomic<bool>& cancel) {
    const std::lock_guard<std::mutex> lock(one_at_a_time);
    std::ostringstream out, err;
    struct Restore {
      std::streambuf *out, *err;
      ~Restore() { std::cout.rdbuf(out), std::cerr.rdbuf(err); }
    } restore{std::cout.rdbuf(out.rdbuf()), std::cerr.rdbuf(err.rdbuf())};
    const cli::EmbeddedInterrupts embedded(&cancel);
    std::vector<const char*> args;
    for (const std::string& a : argv) args.push_back(a.c_str());
    cli::take_output_error();
    c.status = cli::run_cli(int(args.size()), args.data());
    c.output_error = cli::take_output_error();
    c.out = out.str(), c.err = err.str();
  });
  return c;
}

// A str or an os.PathLike as the path it names; none for anything else.
std::optional<std::string> path_text(const py::handle& v) {
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::hasattr(v, "__fspath__")) return py::str(v.attr("__fspath__")()).cast<std::string>();
  return std::nullopt;
}

// The value of keyword `key` as command-line words, or a TypeError naming it.
void add_option(std::vector<std::string>& argv, const std::string& command, const std::string& key,
                const cli::OptionShape& shape, const py::handle& value) {
  const std::string flag = "--" + shape.name;
  const auto wrong = [&](const std::string& what) {
    return py::type_error(command + "(): argument '" + key + "' " + what + ", not " +
                          std::string(py::str(py::type::of(value).attr("__name__"))));
  };
  if (value.is_none()) return;
  if (shape.flag) {
    if (!py::isinstance<py::bool_>(value)) throw wrong("is a flag: True or False");
    if (value.cast<bool>()) argv.push_back(flag);
    return;
  }
  const auto word = [&](const py::handle& v) -> std::string {
    if (py::isinstance<py::bool_>(v)) throw wrong("takes a value");
    if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v)) return py::str(v).cast<std::string>();
    if (std::optional<std::string> path = path_text(v)) return *path;
    throw wrong("takes a string, a number or a path");
  };
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::vector<std::string> words;
    for (const py::handle& v : value) words.push_back(word(v));
    if (words.empty()) return;
    if (shape.several) {
      argv.push_back(flag);
      argv.insert(argv.end(), words.begin(), words.end());
    } else {  // a list option such as --format glb,ply
      std::string joined;
      for (const std::string& w : words) joined += (joined.empty() ? "" : ",") + w;
      argv.push_back(flag), argv.push_back(joined);
    }
    return;
  }
  argv.push_back(flag), argv.push_back(word(value));
}

// The command line of `command` with `positionals` and `kwargs`, plus `machine` (its JSON output flag).
std::vector<std::string> command_line(const std::string& command, const std::vector<std::string>& positionals,
                                      const py::kwargs& kwargs, const std::string& machine) {
  const std::vector<cli::OptionShape> shapes = cli::command_options(command);
  std::vector<std::string> argv = {"dqskin", command};
  for (const auto& [k, v] : kwargs) {
    const std::string key = py::str(k).cast<std::string>();
    std::string name = key;
    for (char& c : name)
      if (c == '_') c = '-';
    const cli::OptionShape* shape = nullptr;
    for (const cli::OptionShape& s : shapes)
      if (s.name == name) shape = &s;
    if (!shape || name == machine.substr(2) || name == "json" || name == "json-progress")
      throw py::type_error(command + "() got an unexpected keyword argument '" + key + "'");
    // bake's dry run prints a plan instead of baking: no summary to return.
    if (command == "bake" && name == "dry-run")
      throw py::type_error("bake() does not take 'dry_run': it prints a plan instead of baking; use the command line");
    add_option(argv, command, key, *shape, v);
  }
  argv.push_back(machine);
  argv.push_back("--");  // whatever a positional holds, it is not a flag
  argv.insert(argv.end(), positionals.begin(), positionals.end());
  return argv;
}

// The CLI's first error line without its "dqskin: " prefix, or all it printed.
std::string error_line(const Captured& c) {
  std::istringstream lines(c.err);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("dqskin: ", 0) == 0 && line.find(": warning: ") == std::string::npos &&
        line.find(": note: ") == std::string::npos)
      return line.substr(8);
  return c.err.empty() ? "exit status " + std::to_string(c.status) : c.err;
}

// Raises the module's exception for a run that produced no report; passes on warnings.
void raise_or_warn(const Captured& c, bool has_report) {
  const py::module_ module = py::module_::import("dqskin");
  if (c.status == cli::kNoGlContext) {
    PyErr_SetString(module.attr("NoGpuContext").ptr(), error_line(c).c_str());
    throw py::error_already_set();
  }
  if (!has_report && c.status != cli::kSuccess) {
    PyErr_SetString(module.attr(c.output_error ? "OutputError" : "InputError").ptr(), error_line(c).c_str());
    throw py::error_already_set();
  }
  std::istringstream lines(c.err);
  const py::object warn = py::module_::import("warnings").attr("warn");
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("dqskin: ", 0) == 0) warn(line.substr(8), module.attr("Warning"), 1);  // at the caller's line
}

py::object parse_json(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

// The last line of --json-progress output whose event is "summary", parsed; None when there is none.
py::object summary_of(const std::string& out) {
  std::istringstream lines(out);
  std::string last;
  for (std::string line; std::getline(lines, line);)
    if (line.find("\"event\":\"summary\"") != std::string::npos) last = line;
  return last.empty() ? py::none() : parse_json(last);
}

std::vector<std::string> paths(const py::handle& value, const char* command, const char* what) {
  std::vector<std::string> out;
  const auto one = [&](const py::handle& v) {
    std::optional<std::string> path = path_text(v);
    if (!path) throw py::type_error(std::string(command) + "(): " + what + " must be a path or a list of paths");
    out.push_back(std::move(*path));
  };
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    for (const py::handle& v : value) one(v);
  } else {
    one(value);
  }
  return out;
}

// A job (bake, report) run with --json-progress: its summary, or the exception of a job it refused.
py::object job_summary(const char* command, const py::object& inputs, const py::kwargs& kwargs) {
  const Captured c = run_captured(command_line(command, paths(inputs, command, "inputs"), kwargs, "--json-progress"));
  py::object summary = summary_of(c.out);
  raise_or_warn(c, !summary.is_none() && c.status != cli::kUsageOrInputError);
  return summary;
}

}  // namespace

void register_commands(py::module_& module) {
  const py::object warning = py::module_::import("builtins").attr("UserWarning");
  module.attr("Warning") = py::module_::import("builtins").attr("type")(
      "Warning", py::make_tuple(warning), py::dict(py::arg("__module__") = "dqskin",
                                                   py::arg("__doc__") = "A warning the command printed."));

  module.def(
      "bake",
      [](const py::object& inputs, const py::kwargs& kwargs) { return job_summary("bake", inputs, kwargs); },
      py::arg("inputs"),
      "bake(inputs, **options) -> dict\n\n"
      "Runs `dqskin bake INPUTS` with options as `dqskin bake --help` lists them, as keyword arguments\n"
      "(out='frames', format='ply,vat' or ['ply', 'vat'], fps=30, anim='Walk', mode='dqs', keys=True, ...).\n"
      "Returns the summary the command prints with --json-progress (files written, frames, failures,\n"
      "manifest). Raises InputError with the command line's message when it refuses the job.");

  module.def(
      "report",
      [](const py::object& inputs, const py::kwargs& kwargs) {
        py::object summary = job_summary("report", inputs, kwargs);
        // Each input's report.json, as the command wrote it, under "reports" (in the order of "files").
        py::list reports;
        // report refuses to run without out=, which may be a number as a folder name
        const std::string out = path_text(kwargs["out"]).value_or(py::str(kwargs["out"]).cast<std::string>());
        for (const py::handle& f : summary["files"]) {
          const std::string file = f.cast<std::string>();
          if (file.ends_with("report.json")) {
            const py::object path = py::module_::import("pathlib").attr("Path")(out, file);
            reports.append(parse_json(path.attr("read_text")(py::arg("encoding") = "utf-8").cast<std::string>()));
          }
        }
        summary["reports"] = reports;
        return summary;
      },
      py::arg("inputs"),
      "report(inputs, **options) -> dict\n\n"
      "Runs `dqskin report INPUTS` with options as keyword arguments (out='reports', anim='Walk', ...).\n"
      "Returns the command's summary with \"reports\": each input's report.json as a dict.");

  module.def(
      "diff",
      [](const py::object& a, const py::object& b, const py::kwargs& kwargs) {
        std::vector<std::string> sides = paths(a, "diff", "a");
        const std::vector<std::string> bs = paths(b, "diff", "b");
        if (sides.size() != 1 || bs.size() != 1) throw py::type_error("diff(): a and b are one path each");
        sides.push_back(bs.front());
        const Captured c = run_captured(command_line("diff", sides, kwargs, "--json"));
        const bool report = !c.out.empty() && c.out.front() == '{';
        raise_or_warn(c, report);
        return parse_json(c.out);
      },
      py::arg("a"), py::arg("b"),
      "diff(a, b, **options) -> dict\n\n"
      "Runs `dqskin diff A B --json` with options as keyword arguments (fail=0.01, relative=True,\n"
      "metric='flip', html='page', ...). Returns the JSON report; its \"status\" is PASS, WARN or FAIL (a\n"
      "failing diff is a result, not an exception).");

  module.def(
      "lint",
      [](const py::object& inputs, const py::kwargs& kwargs) {
        const Captured c = run_captured(command_line("lint", paths(inputs, "lint", "inputs"), kwargs, "--json"));
        const bool report = !c.out.empty() && c.out.front() == '{';
        raise_or_warn(c, report);
        return parse_json(c.out);
      },
      py::arg("inputs"),
      "lint(inputs, **options) -> dict\n\n"
      "Runs `dqskin lint INPUTS --json` with options as keyword arguments (max_influences=4, ...).\n"
      "Returns the JSON report (findings per file; warnings and errors are results, not exceptions).");
}

}  // namespace dqskin::python
