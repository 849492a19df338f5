//! Which channel of a capture is which line of the protocol.
//!
//! Every decoder names its lines by its own options (`--clk`, `--data`,
//! `--ma`, `--line`, `--tx-en`), whose defaults are the dotted paths of a
//! `tbgen gen` VCD. A logic analyser names its channels `D0`, `Channel 3` or
//! whatever the user typed, so `--map clk=D0,data=D1` says it once for any
//! protocol: a key is a line option without its dashes, a value a channel
//! name. `--clk D0` says the same for one line.
//!
//! The map is given to `tbgen decode <protocol>` (and to `tbgen check`
//! after `--`) but read only here, where [`super::read`] looks the lines up:
//! the registry sets it for the length of one decode ([`scoped`]), so that
//! no decoder carries it through its own signature.

use std::cell::RefCell;

use clap::{Arg, ArgMatches, Command};

use crate::{Error, Result};

/// The `--map` option's id and long name.
const MAP: &str = "map";

/// `channel` for each line option named in a `--map` (`clk` → `D0`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LineMap(Vec<(String, String)>);

impl LineMap {
    /// Parses `clk=D0,data=D1` (several `--map` values add up).
    pub fn parse<'a>(values: impl IntoIterator<Item = &'a str>) -> Result<LineMap> {
        let mut pairs = Vec::new();
        for pair in values.into_iter().flat_map(|v| v.split(',')) {
            let (line, channel) = pair
                .split_once('=')
                .map(|(l, c)| (l.trim().trim_start_matches("--"), c.trim()))
                .filter(|(l, c)| !l.is_empty() && !c.is_empty())
                .ok_or_else(|| {
                    Error::Decode(format!(
                        "--map `{pair}`: give line=channel pairs, e.g. --map clk=D0,data=D1"
                    ))
                })?;
            pairs.push((line.to_string(), channel.to_string()));
        }
        Ok(LineMap(pairs))
    }

    /// The name to look up for the line set by `option` (`--clk`): the
    /// mapped channel, else `name` as the option gave it.
    fn channel<'a>(&'a self, name: &'a str, option: &str) -> &'a str {
        let key = option.trim_start_matches("--");
        self.0
            .iter()
            .rev()
            .find(|(l, _)| l == key)
            .map_or(name, |(_, c)| c.as_str())
    }

    /// Refuses a key that is none of the decoder's lines (a typo would
    /// otherwise leave the default in force, silently).
    fn check_keys(&self, options: &[&str]) -> Result<()> {
        let keys: Vec<&str> = options.iter().map(|o| o.trim_start_matches("--")).collect();
        match self.0.iter().find(|(l, _)| !keys.contains(&l.as_str())) {
            Some((l, _)) => Err(Error::Decode(format!(
                "--map {l}=...: `{l}` is not a line of this decoder; its lines: {}",
                keys.join(", ")
            ))),
            None => Ok(()),
        }
    }
}

thread_local! {
    /// The map of the decode under way on this thread ([`scoped`]).
    static CURRENT: RefCell<LineMap> = RefCell::new(LineMap::default());
    /// `(name the decoder asked for, channel read instead)` in that decode.
    static READ: RefCell<Vec<(String, String)>> = const { RefCell::new(Vec::new()) };
}

/// The `--map` option, added to every protocol's decode command.
pub fn with_map_option(cmd: Command) -> Command {
    cmd.arg(
        Arg::new(MAP)
            .long(MAP)
            .value_name("LINE=CHANNEL,...")
            .action(clap::ArgAction::Append)
            .help("Which channel of a logic-analyser capture (.sr, .csv) is which line, e.g. --map clk=D0,data=D1 (a line is a line option without its dashes)"),
    )
}

/// Runs `decode` with the `--map` of `args` in force for [`resolve`]; the
/// transcript it returns names, under `signals`, the channel each mapped
/// line was read from (the decoder names the line as its option gave it).
pub fn scoped(args: &ArgMatches, decode: impl FnOnce() -> Result<String>) -> Result<String> {
    let map = LineMap::parse(
        args.get_many::<String>(MAP)
            .into_iter()
            .flatten()
            .map(String::as_str),
    )?;
    let before = CURRENT.with(|c| c.replace(map));
    let read_before = READ.with(|r| r.take());
    let out = decode();
    CURRENT.with(|c| c.replace(before));
    let read = READ.with(|r| r.replace(read_before));
    let json = out?;
    if read.is_empty() {
        return Ok(json);
    }
    let mut doc: serde_json::Value =
        serde_json::from_str(&json).map_err(|e| Error::Decode(e.to_string()))?;
    if let Some(signals) = doc
        .get_mut("signals")
        .and_then(serde_json::Value::as_object_mut)
    {
        for v in signals.values_mut() {
            if let Some((_, channel)) = read
                .iter()
                .find(|(name, _)| v.as_str() == Some(name.as_str()))
            {
                *v = channel.as_str().into();
            }
        }
    }
    serde_json::to_string_pretty(&doc).map_err(|e| Error::Decode(e.to_string()))
}

/// The names to look up for the decoder's `(name, option)` lines, with the
/// map in force applied.
pub(crate) fn resolve(names: &[(&str, &str)]) -> Result<Vec<String>> {
    let resolved: Vec<String> = CURRENT.with(|c| {
        let map = c.borrow();
        map.check_keys(&names.iter().map(|&(_, o)| o).collect::<Vec<_>>())?;
        Ok::<_, Error>(
            names
                .iter()
                .map(|&(n, o)| map.channel(n, o).to_string())
                .collect(),
        )
    })?;
    READ.with(|r| {
        r.borrow_mut().extend(
            names
                .iter()
                .zip(&resolved)
                .filter(|((n, _), c)| n != c)
                .map(|(&(n, _), c)| (n.to_string(), c.clone())),
        )
    });
    Ok(resolved)
}

/// The index in `channels` of the channel named `name`: that name exactly,
/// else its last dotted part (sigrok's VCD import keeps only a signal's own
/// name, so `top.line.ssi_clk_master` is the channel `ssi_clk_master`).
/// The error lists the channels present.
pub(crate) fn find(channels: &[String], name: &str, option: &str, file: &str) -> Result<usize> {
    let last = name.rsplit('.').next().unwrap_or(name);
    channels
        .iter()
        .position(|c| c == name)
        .or_else(|| channels.iter().position(|c| c == last))
        .ok_or_else(|| {
            Error::Decode(format!(
                "{file}: no channel `{name}` for {option}; the capture's channels: {}; name one with {option} <channel> or --map {}=<channel>",
                if channels.is_empty() { "none".to_string() } else { channels.join(", ") },
                option.trim_start_matches("--")
            ))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_map_names_the_channel_of_each_line_and_refuses_a_line_the_decoder_lacks() {
        let m = LineMap::parse(["clk=D0, data = D1", "tx-en=D3"]).unwrap();
        assert_eq!(m.channel("top.line.clk", "--clk"), "D0");
        assert_eq!(m.channel("top.line.data", "--data"), "D1");
        assert_eq!(m.channel("top.x", "--tx-en"), "D3");
        assert_eq!(m.channel("top.line.ma", "--ma"), "top.line.ma");
        let e = m.check_keys(&["--clk", "--data"]).unwrap_err().to_string();
        assert_eq!(
            e,
            "--map tx-en=...: `tx-en` is not a line of this decoder; its lines: clk, data"
        );
        let e = LineMap::parse(["clk:D0"]).unwrap_err().to_string();
        assert!(e.contains("--map `clk:D0`: give line=channel pairs"), "{e}");
    }

    #[test]
    fn a_missing_channel_lists_the_channels_present() {
        let channels = vec!["D0".to_string(), "D1".to_string()];
        assert_eq!(find(&channels, "D1", "--data", "c.sr").unwrap(), 1);
        let e = find(&channels, "top.line.ssi_clk_master", "--clk", "c.sr")
            .unwrap_err()
            .to_string();
        assert_eq!(e, "c.sr: no channel `top.line.ssi_clk_master` for --clk; the capture's channels: D0, D1; name one with --clk <channel> or --map clk=<channel>");
        let named = vec!["ssi_clk_master".to_string()];
        assert_eq!(
            find(&named, "top.line.ssi_clk_master", "--clk", "c.sr").unwrap(),
            0
        );
    }
}
