#pragma once
// Each subcommand of the `dotvision` CLI lives in its own cmd_<name>.cpp and
// registers itself here. A registration adds the subcommand and its options
// to the root app and returns the function that runs it (its exit code).
// Bad input is thrown as dv::InputError; main turns it into one line, exit 2.
#include <CLI/CLI.hpp>
#include <functional>

namespace dv::app {

using CommandFn = std::function<int()>;

CommandFn addRunCommand(CLI::App& root);
CommandFn addSynthCommand(CLI::App& root);
CommandFn addCalibrateCommand(CLI::App& root);
CommandFn addEvalCommand(CLI::App& root);
CommandFn addBenchCommand(CLI::App& root);
CommandFn addGeometryCommand(CLI::App& root);
CommandFn addServeCommand(CLI::App& root);
CommandFn addCamerasCommand(CLI::App& root);
CommandFn addPlotCommand(CLI::App& root);

// Exit codes shared by all subcommands.
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;     // ran, but the job failed (e.g. quality gate)
constexpr int kExitBadInput = 2;    // unusable input or options
constexpr int kExitUnfinished = 3;  // the subcommand is not built yet

}  // namespace dv::app
