//! The `fiberfold` command line: a thin layer over the library.

mod cli;

fn main() -> std::process::ExitCode {
    // Like other Unix tools, end quietly when the reader of stdout goes away (`| head`)
    // instead of panicking on the failed print.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of SIGPIPE before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    // glibc's malloc gives each thread that allocates an arena of its own and raises its mmap
    // threshold to the size of every large block freed; the per-assembly tangents (10-20 MB on
    // the fine mesh, made on the assembly's threads) then fragment several heaps, so that a
    // run's peak memory depends on incidental allocation order (measured: 308-358 MB for one
    // fine run, by the length of the output path). One arena keeps it at about 300 MB, and
    // the run is as fast.
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: a malloc parameter, set before any thread starts or allocates much.
    unsafe {
        libc::mallopt(libc::M_ARENA_MAX, 1);
    }
    cli::run()
}
