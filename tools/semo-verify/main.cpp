// semo-verify: command-line entry point. Only wires options to the commands.
#include <CLI/CLI.hpp>

#include <iostream>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"semo-verify: check a multi-robot mission (SeMo language) before it is deployed"};
  app.set_version_flag("--version", "semo-verify 0.1.0");
  app.require_subcommand(1);
  app.footer("Exit codes: 0 clean, 1 property violated, 2 bad input, 3 resource limit reached.\n"
             "The language is described in specs/language.md, strategies in specs/strategy.md.");

  semo::cli::ParseOptions parse;
  CLI::App* parseCmd = app.add_subcommand("parse", "Parse a mission and print a summary of its AST (or the AST as JSON)");
  parseCmd->add_option("mission", parse.mission, "Mission file (.semo)")->required();
  parseCmd->add_flag("--json", parse.json, "Print the whole AST as JSON");

  semo::cli::LintOptions lint;
  CLI::App* lintCmd = app.add_subcommand("lint", "Parse and elaborate a mission against its strategy and robots; report every diagnostic");
  lintCmd->add_option("mission", lint.mission, "Mission file (.semo)")->required();
  lintCmd->add_option("--strategy,-s", lint.strategy, "Strategy file (.xml)")->required();
  lintCmd->add_option("--robots,-r", lint.robotsDir,
                      "Folder of URDF files; strategy URDF paths are resolved against it (default: the strategy's folder)");
  lintCmd->add_flag("--warnings-as-errors,-W", lint.warningsAsErrors, "Exit 2 when there is any warning");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the message
    return semo::cli::kBadInput;
  }
  if (*parseCmd) return semo::cli::runParse(parse);
  if (*lintCmd) return semo::cli::runLint(lint);
  return semo::cli::kBadInput;
}
