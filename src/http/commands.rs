//! The binary's commands: `serve` (the default), `healthcheck`, `solve` and
//! `sweep`, each run on a tokio runtime of its own, and `openapi`, `kernels`
//! and `collect`, which need none. `main.rs` only parses the command line and
//! calls [`run_command`].

use std::process::ExitCode;

use tokio::io::{AsyncReadExt, AsyncWriteExt};

use crate::http::config::{Cli, Command};

/// The target of the service's own lines (start-up, bind and key errors):
/// `restitution`, apart from the request handling's `restitution::http`,
/// so that `RESTITUTION_LOG=info,restitution::http=warn` keeps them.
const SERVICE: &str = "restitution";
use crate::http::offline::{self, OfflineError, Shard};

/// Runs the command `cli` names (the service by default).
pub fn run_command(cli: Cli) -> ExitCode {
    if cli.kernels == "portable" {
        crate::kernels::force_portable();
    }
    match cli.command {
        Some(Command::Openapi) => {
            print!("{}", crate::http::openapi_json());
            ExitCode::SUCCESS
        }
        Some(Command::Kernels) => {
            println!("{}", crate::kernels::selected().as_str());
            ExitCode::SUCCESS
        }
        Some(Command::Healthcheck { addr }) => run(healthcheck(addr)),
        Some(Command::Serve(config)) => run(serve(config)),
        Some(Command::Solve { case }) => run(solve(case)),
        Some(Command::Sweep {
            request,
            output,
            format,
            shards,
            index,
        }) => {
            let shard = shards.zip(index).map(|(shards, index)| Shard { shards, index });
            run(sweep(request, output, format, shard))
        }
        Some(Command::Collect { output, parts }) => collect(output, parts),
        None => run(serve(cli.serve)),
    }
}

/// `restitution collect`: the parts checked and joined into `output`.
fn collect(output: std::path::PathBuf, parts: Vec<std::path::PathBuf>) -> ExitCode {
    let opened: Result<Vec<_>, _> = parts
        .iter()
        .map(|p| std::fs::File::open(p).map(|f| (p.display().to_string(), std::io::BufReader::new(f))))
        .collect();
    let result = opened
        .map_err(crate::http::collect::CollectError::from)
        .and_then(|parts| {
            let file = std::fs::File::create(&output)?;
            crate::http::collect::collect(parts, std::io::BufWriter::new(file))
        });
    match result {
        Ok(rows) => {
            eprintln!("restitution collect: {rows} rows in {}", output.display());
            ExitCode::SUCCESS
        }
        Err(error) => {
            eprintln!("restitution collect: {error}");
            let _ = std::fs::remove_file(&output);
            ExitCode::FAILURE
        }
    }
}

/// Runs `task`, then gives blocking work (a sweep whose client is gone) a moment to stop.
fn run(task: impl std::future::Future<Output = ExitCode>) -> ExitCode {
    let runtime = runtime();
    let code = runtime.block_on(task);
    runtime.shutdown_timeout(std::time::Duration::from_secs(1));
    code
}

fn runtime() -> tokio::runtime::Runtime {
    tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .expect("the tokio runtime starts")
}

async fn serve(mut config: crate::http::ServiceConfig) -> ExitCode {
    // One thread writes the log: no write system call on the request path,
    // and the access log's lines are formatted there too (a request hands it
    // its fields). Not lossy: when its queue is full a request waits rather
    // than lose its line. The guard writes out what is queued on the way out.
    let ansi = std::io::IsTerminal::is_terminal(&std::io::stdout());
    let (writer, _flush_on_exit) = match crate::http::log::spawn(std::io::stdout(), ansi) {
        Ok(spawned) => spawned,
        Err(error) => {
            eprintln!("restitution: cannot start the log writer: {error}");
            return ExitCode::FAILURE;
        }
    };
    tracing_subscriber::fmt()
        .with_ansi(ansi)
        .with_writer(writer.clone())
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_env("RESTITUTION_LOG")
                .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("info")),
        )
        .init();
    // The access log at the level `RESTITUTION_LOG` gives its target, checked
    // once here rather than per request.
    crate::http::log::install_access_log(&writer, crate::http::log::access_log_level());
    if let Err(error) = config.load_api_key() {
        tracing::error!(target: SERVICE, %error, "cannot read the API key");
        return ExitCode::FAILURE;
    }
    let listener = match tokio::net::TcpListener::bind(config.bind).await {
        Ok(listener) => listener,
        Err(error) => {
            tracing::error!(target: SERVICE, %error, bind = %config.bind, "cannot bind");
            return ExitCode::FAILURE;
        }
    };
    // The address actually bound (a port of 0 is chosen by the system), and
    // the explorer's URL to open.
    let bound = listener.local_addr().unwrap_or(config.bind);
    let host = match bound.ip() {
        ip if ip.is_unspecified() => "127.0.0.1".to_string(),
        std::net::IpAddr::V6(ip) => format!("[{ip}]"),
        ip => ip.to_string(),
    };
    tracing::info!(
        target: SERVICE,
        bind = %bound,
        explorer = %format!("http://{host}:{}/", bound.port()),
        kernels = crate::kernels::selected().as_str(),
        "listening"
    );
    match crate::http::serve(listener, &config).await {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            tracing::error!(target: SERVICE, %error, "server failed");
            ExitCode::FAILURE
        }
    }
}

async fn healthcheck(addr: std::net::SocketAddr) -> ExitCode {
    let attempt = async {
        let mut stream = tokio::net::TcpStream::connect(addr).await?;
        stream
            .write_all(
                format!("GET /healthz HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n").as_bytes(),
            )
            .await?;
        let mut head = [0u8; 12];
        stream.read_exact(&mut head).await?;
        Ok::<bool, std::io::Error>(head.starts_with(b"HTTP/1.1 200"))
    };
    match tokio::time::timeout(std::time::Duration::from_secs(3), attempt).await {
        Ok(Ok(true)) => ExitCode::SUCCESS,
        _ => ExitCode::FAILURE,
    }
}

async fn solve(case: String) -> ExitCode {
    let stdin = std::io::stdin().lock();
    let stdout = std::io::BufWriter::new(std::io::stdout().lock());
    match offline::solve(&case, stdin, stdout).await {
        Ok(0) => ExitCode::SUCCESS,
        Ok(_) => ExitCode::from(1),
        Err(error) => {
            eprintln!("restitution solve: {error}");
            ExitCode::from(2)
        }
    }
}

async fn sweep(
    request: std::path::PathBuf,
    output: Option<std::path::PathBuf>,
    format: Option<String>,
    shard: Option<Shard>,
) -> ExitCode {
    let format = format
        .or_else(|| {
            output
                .as_ref()
                .and_then(|o| o.extension())
                .map(|e| e.to_string_lossy().into_owned())
        })
        .unwrap_or_else(|| "csv".to_owned());
    let Some(accept) = offline::accept_for(&format) else {
        eprintln!("restitution sweep: unknown format {format:?}: csv, ndjson, arrow, json or svg");
        return ExitCode::from(2);
    };
    let result = match &output {
        Some(path) => match std::fs::File::create(path) {
            Ok(file) => offline::sweep(&request, shard, accept, std::io::BufWriter::new(file)).await,
            Err(error) => Err(OfflineError::Io(error)),
        },
        None => offline::sweep(&request, shard, accept, std::io::stdout().lock()).await,
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("restitution sweep: {error}");
            ExitCode::from(if matches!(error, OfflineError::Refused(_)) {
                1
            } else {
                2
            })
        }
    }
}
