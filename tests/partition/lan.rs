//! A local network of hosts for tests: one network namespace per host, each with a veth cable
//! to one bridge, and nftables rules in each host that drop a share of what it receives (loss)
//! or everything it sends and receives (a cut). Made as root with `ip` and `nft`; where the
//! machine cannot, [`Lan::new`] says why and the test checks nothing. Dropped, it removes every
//! namespace and the bridge.

use std::process::{Command, Output, Stdio};

/// A network of `hosts`, named `<tag>h1`…, at 10.77.0.1… on one bridge.
pub struct Lan {
    bridge: String,
    hosts: Vec<String>,
}

impl Lan {
    /// Makes a network of `count` hosts, or says why it cannot be made here.
    pub fn new(count: usize) -> Result<Lan, String> {
        for tool in ["ip", "nft"] {
            if !Command::new(tool)
                .arg("-V")
                .stdout(Stdio::null())
                .stderr(Stdio::null())
                .status()
                .is_ok_and(|s| s.success())
            {
                return Err(format!("`{tool}` is not installed (iproute2, nftables)"));
            }
        }
        // Unique to this network of this test process: interface names are at most 15
        // characters.
        static MADE: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let made = MADE.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let tag = format!("pc{}x{made}", std::process::id());
        let mut lan = Lan {
            bridge: format!("{tag}b"),
            hosts: Vec::new(),
        };
        run("ip", &["link", "add", &lan.bridge, "type", "bridge"])
            .map_err(|e| format!("cannot make a bridge (root and CAP_NET_ADMIN needed): {e}"))?;
        run("ip", &["link", "set", &lan.bridge, "up"])?;
        for i in 1..=count {
            let host = format!("{tag}h{i}");
            run("ip", &["netns", "add", &host])?;
            lan.hosts.push(host.clone());
            let cable = format!("{tag}v{i}");
            run(
                "ip",
                &[
                    "link", "add", &cable, "type", "veth", "peer", "name", "eth0", "netns", &host,
                ],
            )?;
            run("ip", &["link", "set", &cable, "master", &lan.bridge, "up"])?;
            let address = format!("{}/24", lan.address(i));
            lan.inside(i, "ip", &["addr", "add", &address, "dev", "eth0"])?;
            lan.inside(i, "ip", &["link", "set", "eth0", "up"])?;
            lan.inside(i, "ip", &["link", "set", "lo", "up"])?;
            lan.inside(i, "nft", &["add", "table", "inet", "fault"])?;
            for (chain, hook) in [("in", "input"), ("out", "output")] {
                let spec = format!("{{ type filter hook {hook} priority 0; }}");
                lan.inside(i, "nft", &["add", "chain", "inet", "fault", chain, &spec])?;
            }
        }
        Ok(lan)
    }

    /// Host `i`'s address (hosts count from 1). Every network uses the same addresses: each
    /// host is a namespace of its own and the bridge has none.
    pub fn address(&self, i: usize) -> String {
        format!("10.77.0.{i}")
    }

    /// A command run inside host `i`.
    pub fn command(&self, i: usize, program: &str) -> Command {
        let mut command = Command::new("ip");
        command
            .args(["netns", "exec", &self.hosts[i - 1], program])
            .env("NO_COLOR", "1");
        command
    }

    /// Host `i` loses `percent` of the packets it receives, and none it sends.
    pub fn lose(&self, i: usize, percent: u32) -> Result<(), String> {
        self.flush(i)?;
        if percent > 0 {
            let rule = format!("iifname eth0 numgen random mod 100 < {percent} drop");
            self.rule(i, "in", &rule)?;
        }
        Ok(())
    }

    /// Cuts host `i` off: nothing in, nothing out, until [`Lan::lose`] sets its loss again.
    pub fn cut(&self, i: usize) -> Result<(), String> {
        self.flush(i)?;
        self.rule(i, "in", "iifname eth0 drop")?;
        self.rule(i, "out", "oifname eth0 drop")
    }

    fn flush(&self, i: usize) -> Result<(), String> {
        for chain in ["in", "out"] {
            self.inside(i, "nft", &["flush", "chain", "inet", "fault", chain])?;
        }
        Ok(())
    }

    fn rule(&self, i: usize, chain: &str, rule: &str) -> Result<(), String> {
        let mut args = vec!["add", "rule", "inet", "fault", chain];
        args.extend(rule.split(' '));
        self.inside(i, "nft", &args)
    }

    fn inside(&self, i: usize, program: &str, args: &[&str]) -> Result<(), String> {
        let mut all = vec!["netns", "exec", self.hosts[i - 1].as_str(), program];
        all.extend_from_slice(args);
        run("ip", &all)
    }
}

impl Drop for Lan {
    fn drop(&mut self) {
        for host in &self.hosts {
            let _ = run("ip", &["netns", "del", host]);
        }
        let _ = run("ip", &["link", "del", &self.bridge]);
    }
}

fn run(program: &str, args: &[&str]) -> Result<(), String> {
    let output: Output = Command::new(program)
        .args(args)
        .output()
        .map_err(|e| format!("{program}: {e}"))?;
    if output.status.success() {
        Ok(())
    } else {
        Err(format!(
            "`{program} {}`: {}",
            args.join(" "),
            String::from_utf8_lossy(&output.stderr).trim()
        ))
    }
}
