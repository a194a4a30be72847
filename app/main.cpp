// dqskin command line: CLI11 fills the settings, one function per command runs it.
#include "exit_codes.hpp"

#include "dqskin/version.hpp"

#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

int main(int argc, char** argv) {
  using namespace dqskin::cli;

  CLI::App app{
      "dqskin: deforms the skinned meshes of glTF 2.0 animations with dual quaternions (Kavan et al.), "
      "headless, for asset builds and CI.",
      "dqskin"};
  app.set_version_flag("--version", std::string("dqskin ") + dqskin::kVersion, "Print the version and exit");
  app.footer(
      "Exit status: 0 success, 1 some inputs failed, 2 usage or input error, 3 no OpenGL context.");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return kSuccess;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << '\n';
    return kSuccess;
  } catch (const CLI::ParseError& e) {
    std::cerr << "dqskin: " << e.what() << " (see dqskin --help)\n";
    return kUsageOrInputError;
  }

  // No command given: show what there is to run.
  std::cout << app.help();
  return kSuccess;
}
