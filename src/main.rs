//! The `restitution` binary: parses the command line and runs it
//! ([`restitution::http::commands`]).

use clap::Parser;

fn main() -> std::process::ExitCode {
    restitution::http::commands::run_command(restitution::http::config::Cli::parse())
}
