// The host programs' command lines (CLI11) end the same way: --help on stdout with exit code 0, a bad
// command line as one line "PROGRAM: error: ... (see --help)" on stderr with exit code 2, and a run
// that fails as "PROGRAM: error: WHAT" with exit code 1 (host/README.md, "Exit codes"). Written once
// here for tvo_sim, tvo_soak, tvo_rtbench_report, tvo_fleet_hub, log2csv and tvo_study.
#pragma once

#include <exception>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

namespace tvo_options {

/// parse_command_line's answer when the program should go on and run.
constexpr int kRun = -1;
/// The exit code of a bad command line (a parse error or a rule between options).
constexpr int kBadCommandLine = 2;
/// The exit code of a run that failed.
constexpr int kRunFailed = 1;

/// CLI11's message on one line: its line breaks as blanks, no blank at the end.
inline std::string one_line(std::string text)
{
    for (char& c : text) {
        c = (c == '\n') ? ' ' : c;
    }
    while (!text.empty() && text.back() == ' ') {
        text.pop_back();
    }
    return text;
}

/// Names the option and why it is refused, "PROGRAM: error: OPTION: WHY (see --help)" on stderr;
/// returns kBadCommandLine.
inline int option_error(const std::string& program, const std::string& option, const std::string& why)
{
    std::cerr << program << ": error: " << option << ": " << why << " (see --help)\n";
    return kBadCommandLine;
}

/// Parses argv into app. Returns kRun to go on, 0 after --help (printed on stdout), or
/// kBadCommandLine after CLI11's refusal on one line on stderr.
inline int parse_command_line(CLI::App& app, int argc, char** argv, const std::string& program)
{
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        std::cout << app.help();
        return 0;
    } catch (const CLI::CallForAllHelp&) {
        std::cout << app.help("", CLI::AppFormatMode::All);
        return 0;
    } catch (const CLI::ParseError& e) {
        std::cerr << program << ": error: " << one_line(e.what()) << " (see --help)\n";
        return kBadCommandLine;
    }
    return kRun;
}

/// Runs body (which returns the exit code); an exception it throws is reported as
/// "PROGRAM: error: WHAT" on stderr with kRunFailed.
template <class Body>
int run_reporting_errors(const std::string& program, Body&& body)
{
    try {
        return body();
    } catch (const std::exception& e) {
        std::cerr << program << ": error: " << e.what() << '\n';
        return kRunFailed;
    }
}

}  // namespace tvo_options
