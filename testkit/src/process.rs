//! A release or debug binary of the service as a child process: a free
//! loopback port for it, and a raw connection once it listens.

use std::net::{TcpListener, TcpStream};
use std::time::{Duration, Instant};

/// A port no one listens on now, on 127.0.0.1.
pub fn free_port() -> u16 {
    TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

/// A connection to the server on `port`, waiting up to 20 s for it to listen.
pub fn connect(port: u16) -> TcpStream {
    let deadline = Instant::now() + Duration::from_secs(20);
    loop {
        match TcpStream::connect(("127.0.0.1", port)) {
            Ok(stream) => {
                stream.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
                return stream;
            }
            Err(_) if Instant::now() < deadline => std::thread::sleep(Duration::from_millis(10)),
            Err(error) => panic!("the server does not accept connections: {error}"),
        }
    }
}
