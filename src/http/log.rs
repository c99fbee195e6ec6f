//! The service's log output, written by a thread of its own: no formatting
//! and no write system call for the access log on the request path.
//!
//! [`spawn`] starts the writer thread and gives a [`LogWriter`] (the
//! `tracing` subscriber's writer: lines formatted by the subscriber are queued
//! as they are) and a [`FlushGuard`] (dropping it writes out what is queued).
//! [`install_access_log`] routes the access log through the same queue: a
//! request hands its raw fields (time, level, request id, method, path,
//! status, latency, panic message) to the thread, which formats the line as
//! `tracing_subscriber::fmt` does (the same text, byte for byte, ANSI colours
//! included). Without it (a library user, the tests) the access log is a
//! `tracing` event at the target [`ACCESS_TARGET`].
//!
//! The queue is bounded and not lossy: when it is full a request waits for
//! room rather than lose its line. One thread writes everything, in order.
//! Against `tracing-appender`'s lossless non-blocking writer, side by side:
//! 11–19 % more requests per second, identical servers within 2 %
//! (`benches/scripts/hand-vs-crates`; docs/performance-log.md).

use std::io::Write;
use std::sync::OnceLock;
use std::sync::mpsc::{Receiver, SyncSender, TryRecvError};
use std::time::{Duration, SystemTime};

use axum::http::Method;
use tracing::Level;
use tracing::level_filters::LevelFilter;

/// The target of the access log's lines (the `restitution::http` module's, as
/// the `tracing` events it replaces had): what `RESTITUTION_LOG` directives
/// name to filter it.
pub const ACCESS_TARGET: &str = "restitution::http";

/// Lines queued at most; a request waits when the queue is full.
const QUEUE: usize = 4096;

/// How long the writer thread sleeps after writing a batch before it looks
/// for more. Under load, lines arrive within this time and the thread takes
/// them without being woken (a request never pays for waking it); when the
/// queue stays empty it waits to be woken by the next line. Each wake-up of
/// the thread costs the request path too, on a machine whose cores the
/// workers keep busy (a context switch, a worker pre-empted): 10 ms took
/// fewer context switches per request than 1 ms in every round measured,
/// and about 7 % less CPU per request on average (docs/performance-log.md,
/// "Two changes measured together").
const LINGER: Duration = Duration::from_millis(10);

/// The linger after a batch of more than a quarter of the queue: lines are
/// then arriving fast enough to fill the queue within a few lingers, and a
/// full queue makes requests wait for room.
const SHORT_LINGER: Duration = Duration::from_millis(1);

/// What the writer thread is sent.
enum Message {
    /// An access-log line, formatted by the thread.
    Access(AccessRecord),
    /// A line formatted by the `tracing` subscriber.
    Line(Vec<u8>),
    /// Write out everything queued before, flush, and answer.
    Flush(SyncSender<()>),
}

/// The fields of one access-log line, copied out of the request: nothing
/// in it refers to the request's buffers (which the connection would then
/// have to replace rather than reuse, and this thread free).
struct AccessRecord {
    time: SystemTime,
    level: Level,
    request_id: Text,
    method: Method,
    path: Text,
    status: u16,
    latency_us: u64,
    /// The panic message of a 500 from a handler's panic (logged at error).
    panic: Option<Box<str>>,
}

/// A short text held inline (no allocation), a longer one on the heap.
enum Text {
    Inline(u8, [u8; 62]),
    Heap(Box<[u8]>),
}

impl Text {
    fn new(text: &str) -> Text {
        let bytes = text.as_bytes();
        let mut inline = [0u8; 62];
        match inline.get_mut(..bytes.len()) {
            Some(head) => {
                head.copy_from_slice(bytes);
                Text::Inline(bytes.len() as u8, inline)
            }
            None => Text::Heap(bytes.into()),
        }
    }

    fn bytes(&self) -> &[u8] {
        match self {
            Text::Inline(len, bytes) => &bytes[..usize::from(*len)],
            Text::Heap(bytes) => bytes,
        }
    }
}

/// Queues lines for the writer thread: the `tracing` subscriber's writer
/// (`tracing_subscriber::fmt().with_writer(writer)`), one `write` per line.
#[derive(Clone, Debug)]
pub struct LogWriter {
    sender: SyncSender<Message>,
}

impl Write for LogWriter {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.sender
            .send(Message::Line(bytes.to_vec()))
            .map_err(|_| std::io::Error::other("the log writer thread is gone"))?;
        Ok(bytes.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl<'a> tracing_subscriber::fmt::MakeWriter<'a> for LogWriter {
    type Writer = LogWriter;

    fn make_writer(&'a self) -> LogWriter {
        self.clone()
    }
}

/// Writes out what is queued when dropped (waiting at most a second for the
/// writer thread), or on [`FlushGuard::flush`].
#[derive(Debug)]
pub struct FlushGuard {
    sender: SyncSender<Message>,
}

impl FlushGuard {
    /// Waits (at most `timeout`) until every line queued before this call is
    /// written and the output flushed; false if that did not happen in time.
    pub fn flush(&self, timeout: Duration) -> bool {
        let (ack, done) = std::sync::mpsc::sync_channel(1);
        if self.sender.send(Message::Flush(ack)).is_err() {
            return false;
        }
        done.recv_timeout(timeout).is_ok()
    }
}

impl Drop for FlushGuard {
    fn drop(&mut self) {
        self.flush(Duration::from_secs(1));
    }
}

/// Starts the thread that writes the log to `out`, with ANSI colours in the
/// access log's lines when `ansi` (as the subscriber has them).
pub fn spawn<W: Write + Send + 'static>(out: W, ansi: bool) -> std::io::Result<(LogWriter, FlushGuard)> {
    let (sender, receiver) = std::sync::mpsc::sync_channel(QUEUE);
    std::thread::Builder::new()
        .name("log-writer".to_owned())
        .spawn(move || write_lines(receiver, out, ansi))?;
    Ok((
        LogWriter {
            sender: sender.clone(),
        },
        FlushGuard { sender },
    ))
}

/// The writer thread: takes whatever is queued, formats it into one buffer,
/// writes it with one call, then lingers before looking again.
fn write_lines<W: Write>(receiver: Receiver<Message>, mut out: W, ansi: bool) {
    let mut buffer = Vec::with_capacity(64 * 1024);
    // Blocks only when the queue has been empty for a whole linger.
    while let Ok(first) = receiver.recv() {
        let mut next = Some(first);
        loop {
            let mut taken = 0;
            while let Some(message) = next.take().or_else(|| receiver.try_recv().ok()) {
                taken += 1;
                match message {
                    Message::Access(record) => format_access(&mut buffer, &record, ansi),
                    Message::Line(line) => buffer.extend_from_slice(&line),
                    Message::Flush(ack) => {
                        write_out(&mut out, &mut buffer);
                        let _ = out.flush();
                        let _ = ack.send(());
                    }
                }
                if buffer.len() >= 60 * 1024 {
                    write_out(&mut out, &mut buffer);
                }
            }
            write_out(&mut out, &mut buffer);
            let _ = out.flush();
            // A sleep, not a wait on the queue: a sender wakes only a
            // thread waiting on the queue.
            std::thread::sleep(if taken > QUEUE / 4 { SHORT_LINGER } else { LINGER });
            match receiver.try_recv() {
                Ok(message) => next = Some(message),
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => return,
            }
        }
    }
}

/// Writes the buffer out and empties it. A failing output (a closed pipe)
/// loses the lines; the service goes on.
fn write_out<W: Write>(out: &mut W, buffer: &mut Vec<u8>) {
    if !buffer.is_empty() {
        let _ = out.write_all(buffer);
        buffer.clear();
    }
}

/// The access log routed through a writer thread, with the most verbose
/// level its filter lets through.
struct AccessLog {
    sender: SyncSender<Message>,
    max_level: LevelFilter,
}

static ACCESS_LOG: OnceLock<AccessLog> = OnceLock::new();

/// Routes the access log through `writer`'s thread, writing the lines at
/// `max_level` and above ([`access_log_level`] gives the level the installed
/// `tracing` subscriber lets through). Once per process: false if the access
/// log was routed already.
pub fn install_access_log(writer: &LogWriter, max_level: LevelFilter) -> bool {
    ACCESS_LOG
        .set(AccessLog {
            sender: writer.sender.clone(),
            max_level,
        })
        .is_ok()
}

/// The most verbose level of the access log's target ([`ACCESS_TARGET`])
/// the global `tracing` subscriber lets through (its `RESTITUTION_LOG`
/// filter): call it after the subscriber is installed.
pub fn access_log_level() -> LevelFilter {
    if tracing::enabled!(target: "restitution::http", Level::INFO) {
        LevelFilter::INFO
    } else if tracing::enabled!(target: "restitution::http", Level::WARN) {
        LevelFilter::WARN
    } else if tracing::enabled!(target: "restitution::http", Level::ERROR) {
        LevelFilter::ERROR
    } else {
        LevelFilter::OFF
    }
}

/// Whether an access line at `level` would be written (cheap: a load and a
/// comparison once the access log is routed through the writer thread).
pub(crate) fn access_enabled(level: Level) -> bool {
    match ACCESS_LOG.get() {
        Some(log) => level <= log.max_level,
        None => match level {
            Level::ERROR => tracing::enabled!(target: "restitution::http", Level::ERROR),
            Level::WARN => tracing::enabled!(target: "restitution::http", Level::WARN),
            _ => tracing::enabled!(target: "restitution::http", Level::INFO),
        },
    }
}

/// Writes one access-log line (check [`access_enabled`] first): queued for
/// the writer thread when the access log is routed through it, else a
/// `tracing` event.
pub(crate) fn access(
    level: Level,
    request_id: &str,
    method: &Method,
    path: &str,
    status: u16,
    latency_us: u64,
    panic: Option<&str>,
) {
    if let Some(log) = ACCESS_LOG.get() {
        if level <= log.max_level {
            let record = AccessRecord {
                time: SystemTime::now(),
                level,
                request_id: Text::new(request_id),
                method: method.clone(),
                path: Text::new(path),
                status,
                latency_us,
                panic: panic.map(Box::from),
            };
            // Waits when the queue is full; fails only when the thread is gone.
            let _ = log.sender.send(Message::Access(record));
        }
        return;
    }
    let id = request_id;
    match level {
        Level::ERROR => {
            let panic = panic.unwrap_or("");
            tracing::error!(target: "restitution::http", request_id = %id, method = %method, path = %path, status, latency_us, panic, "request");
        }
        Level::WARN => {
            tracing::warn!(target: "restitution::http", request_id = %id, method = %method, path = %path, status, latency_us, "request")
        }
        _ => {
            tracing::info!(target: "restitution::http", request_id = %id, method = %method, path = %path, status, latency_us, "request")
        }
    }
}

/// Formats `record` as `tracing_subscriber::fmt` formats the access log's
/// event: timestamp, level, target, message, then `name=value` fields.
fn format_access(buffer: &mut Vec<u8>, record: &AccessRecord, ansi: bool) {
    const DIM: &[u8] = b"\x1b[2m";
    const ITALIC: &[u8] = b"\x1b[3m";
    const RESET: &[u8] = b"\x1b[0m";
    if ansi {
        buffer.extend_from_slice(DIM);
    }
    write_timestamp(buffer, record.time);
    if ansi {
        buffer.extend_from_slice(RESET);
    }
    buffer.push(b' ');
    let (level, colour): (&[u8], &[u8]) = match record.level {
        Level::ERROR => (b"ERROR", b"\x1b[31m"),
        Level::WARN => (b" WARN", b"\x1b[33m"),
        Level::INFO => (b" INFO", b"\x1b[32m"),
        Level::DEBUG => (b"DEBUG", b"\x1b[34m"),
        Level::TRACE => (b"TRACE", b"\x1b[35m"),
    };
    // `text`, in `style` (then reset) when the output takes ANSI colours.
    let styled = |buffer: &mut Vec<u8>, style: &[u8], text: &[u8]| {
        if ansi {
            buffer.extend_from_slice(style);
            buffer.extend_from_slice(text);
            buffer.extend_from_slice(RESET);
        } else {
            buffer.extend_from_slice(text);
        }
    };
    styled(buffer, colour, level);
    buffer.push(b' ');
    styled(buffer, DIM, ACCESS_TARGET.as_bytes());
    styled(buffer, DIM, b":");
    buffer.extend_from_slice(b" request");
    let field = |buffer: &mut Vec<u8>, name: &str| {
        buffer.push(b' ');
        styled(buffer, ITALIC, name.as_bytes());
        styled(buffer, DIM, b"=");
    };
    field(buffer, "request_id");
    buffer.extend_from_slice(record.request_id.bytes());
    field(buffer, "method");
    buffer.extend_from_slice(record.method.as_str().as_bytes());
    field(buffer, "path");
    buffer.extend_from_slice(record.path.bytes());
    field(buffer, "status");
    write_decimal(buffer, u64::from(record.status));
    field(buffer, "latency_us");
    write_decimal(buffer, record.latency_us);
    if record.level == Level::ERROR {
        field(buffer, "panic");
        // A `&str` field is written with `Debug`: quoted and escaped.
        let _ = write!(buffer, "{:?}", record.panic.as_deref().unwrap_or(""));
    }
    buffer.push(b'\n');
}

/// `n` in decimal.
fn write_decimal(buffer: &mut Vec<u8>, n: u64) {
    write_padded(buffer, n, 0);
}

/// `n` in decimal with at least `width` digits.
fn write_padded(buffer: &mut Vec<u8>, n: u64, width: usize) {
    let mut digits = itoa::Buffer::new();
    let digits = digits.format(n).as_bytes();
    for _ in digits.len()..width {
        buffer.push(b'0');
    }
    buffer.extend_from_slice(digits);
}

/// `time` as RFC 3339 in UTC with microseconds (`2026-11-25T20:54:26.123456Z`),
/// as `tracing_subscriber`'s default timer writes it.
fn write_timestamp(buffer: &mut Vec<u8>, time: SystemTime) {
    let (seconds, nanos) = match time.duration_since(SystemTime::UNIX_EPOCH) {
        Ok(d) => (d.as_secs() as i64, d.subsec_nanos()),
        Err(e) => {
            let d = e.duration();
            match d.subsec_nanos() {
                0 => (-(d.as_secs() as i64), 0),
                n => (-(d.as_secs() as i64) - 1, 1_000_000_000 - n),
            }
        }
    };
    let days = seconds.div_euclid(86_400);
    let second_of_day = seconds.rem_euclid(86_400) as u64;
    let (year, month, day) = civil_from_days(days);
    if year > 9999 {
        buffer.push(b'+');
        write_decimal(buffer, year as u64);
    } else if year < 0 {
        let _ = write!(buffer, "{year:05}");
    } else {
        write_padded(buffer, year as u64, 4);
    }
    buffer.push(b'-');
    write_padded(buffer, month, 2);
    buffer.push(b'-');
    write_padded(buffer, day, 2);
    buffer.push(b'T');
    write_padded(buffer, second_of_day / 3600, 2);
    buffer.push(b':');
    write_padded(buffer, second_of_day / 60 % 60, 2);
    buffer.push(b':');
    write_padded(buffer, second_of_day % 60, 2);
    buffer.push(b'.');
    write_padded(buffer, u64::from(nanos / 1_000), 6);
    buffer.push(b'Z');
}

/// The proleptic Gregorian date of `days` since 1970-01-01 (H. Hinnant's
/// `civil_from_days`).
fn civil_from_days(days: i64) -> (i64, u64, u64) {
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = (doy - (153 * mp + 2) / 5 + 1) as u64;
    let month = (if mp < 10 { mp + 3 } else { mp - 9 }) as u64;
    let year = yoe + era * 400 + i64::from(month <= 2);
    (year, month, day)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A writer into a shared buffer.
    #[derive(Clone, Default)]
    struct Shared(std::sync::Arc<std::sync::Mutex<Vec<u8>>>);

    impl Write for Shared {
        fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
            self.0.lock().unwrap().extend_from_slice(bytes);
            Ok(bytes.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    impl Shared {
        fn text(&self) -> String {
            String::from_utf8(self.0.lock().unwrap().clone()).unwrap()
        }
    }

    fn record(level: Level, status: u16, panic: Option<&str>) -> AccessRecord {
        AccessRecord {
            time: SystemTime::now(),
            level,
            request_id: Text::new("18f0a3c2b1d-42"),
            method: Method::POST,
            path: Text::new("/v1/impacts/oblique"),
            status,
            latency_us: 1234,
            panic: panic.map(Box::from),
        }
    }

    /// The line `tracing_subscriber::fmt` writes for the event the access log
    /// was before it moved to the writer thread.
    fn by_tracing(record: &AccessRecord, ansi: bool) -> String {
        let out = Shared::default();
        let sink = out.clone();
        let subscriber = tracing_subscriber::fmt()
            .with_ansi(ansi)
            .with_max_level(Level::TRACE)
            .with_writer(move || sink.clone())
            .finish();
        tracing::subscriber::with_default(subscriber, || {
            let id = std::str::from_utf8(record.request_id.bytes()).unwrap();
            let method = &record.method;
            let path = std::str::from_utf8(record.path.bytes()).unwrap();
            let (status, latency_us) = (record.status, record.latency_us);
            match record.level {
                Level::ERROR => {
                    let panic = record.panic.as_deref().unwrap_or("");
                    tracing::error!(target: "restitution::http", request_id = %id, method = %method, path = %path, status, latency_us, panic, "request");
                }
                Level::WARN => {
                    tracing::warn!(target: "restitution::http", request_id = %id, method = %method, path = %path, status, latency_us, "request")
                }
                _ => {
                    tracing::info!(target: "restitution::http", request_id = %id, method = %method, path = %path, status, latency_us, "request")
                }
            }
        });
        out.text()
    }

    /// The text after the timestamp (and its colour codes).
    fn after_time(line: &str) -> &str {
        let z = line.find("Z").expect("a timestamp");
        &line[z + 1..]
    }

    #[test]
    fn lines_are_the_subscribers_byte_for_byte() {
        for ansi in [false, true] {
            for record in [
                record(Level::INFO, 200, None),
                record(Level::WARN, 503, None),
                record(Level::ERROR, 500, Some("the \"handler\" broke\n")),
            ] {
                let mut ours = Vec::new();
                format_access(&mut ours, &record, ansi);
                let ours = String::from_utf8(ours).unwrap();
                let theirs = by_tracing(&record, ansi);
                assert_eq!(after_time(&ours), after_time(&theirs), "ansi {ansi}");
                assert_eq!(ours.lines().count(), 1);
            }
        }
    }

    #[test]
    fn texts_short_and_long() {
        for text in ["", "/", &"x".repeat(62), &"y".repeat(63), &"é".repeat(100)] {
            assert_eq!(Text::new(text).bytes(), text.as_bytes());
        }
    }

    #[test]
    fn timestamps_are_the_subscribers() {
        for seconds in [0u64, 951_782_400, 1_764_104_066, 4_102_444_799, 253_402_300_799] {
            let time = SystemTime::UNIX_EPOCH + Duration::new(seconds, 123_456_789);
            let mut ours = Vec::new();
            write_timestamp(&mut ours, time);
            let ours = String::from_utf8(ours).unwrap();
            // The subscriber's formatter is private; check against the civil
            // calendar by hand for a few known instants.
            let expected = match seconds {
                0 => "1970-01-01T00:00:00.123456Z",
                951_782_400 => "2000-02-29T00:00:00.123456Z",
                1_764_104_066 => "2025-11-25T20:54:26.123456Z",
                4_102_444_799 => "2099-12-31T23:59:59.123456Z",
                _ => "9999-12-31T23:59:59.123456Z",
            };
            assert_eq!(ours, expected);
        }
        let mut ours = Vec::new();
        write_timestamp(&mut ours, SystemTime::UNIX_EPOCH - Duration::new(1, 500_000_000));
        assert_eq!(String::from_utf8(ours).unwrap(), "1969-12-31T23:59:58.500000Z");
    }

    #[test]
    fn the_thread_writes_in_order_and_flushes() {
        let out = Shared::default();
        let (mut writer, guard) = spawn(out.clone(), false).unwrap();
        writer.write_all(b"first\n").unwrap();
        for i in 0..10_000u64 {
            let mut r = record(Level::INFO, 200, None);
            r.latency_us = i;
            writer.sender.send(Message::Access(r)).unwrap();
        }
        writer.write_all(b"last\n").unwrap();
        assert!(guard.flush(Duration::from_secs(10)));
        let text = out.text();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 10_002);
        assert_eq!(lines[0], "first");
        assert_eq!(lines[10_001], "last");
        for (i, line) in lines[1..10_001].iter().enumerate() {
            assert!(line.ends_with(&format!(" latency_us={i}")), "{line}");
        }
        drop(guard);
    }
}
