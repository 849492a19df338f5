//! `tbgen eds`: the electronic data sheet (CiA 306, EDS 4.0) of the DS 406
//! encoder `model::canopen` emulates, written from the emulator's own object
//! dictionary (`model::canopen::od::Dictionary`), so the two cannot differ.
//!
//! Node-dependent defaults (the TPDO COB-IDs) are written as `$NODEID+0x180`
//! as CiA 306 allows; a tool substitutes the node it configures.

use std::fmt::Write as _;

use model::canopen::encoder::{EncoderConfig, BIT_RATES_KBPS};
use model::canopen::od::{value, DataType, Dictionary, Object, Sub};

fn default_text(index: u16, s: &Sub, node: u8) -> String {
    match s.dtype {
        DataType::VisibleString => String::from_utf8_lossy(&s.default).into_owned(),
        DataType::Integer32 => format!("{}", value(&s.default) as i32),
        _ => {
            let v = value(&s.default);
            if (index == 0x1800 || index == 0x1801) && s.sub == 1 {
                format!("$NODEID+0x{:X}", v - node as u32)
            } else {
                format!("0x{v:X}")
            }
        }
    }
}

fn entry(out: &mut String, section: &str, index: u16, s: &Sub, node: u8) {
    let _ = writeln!(out, "[{section}]");
    let _ = writeln!(out, "ParameterName={}", s.name);
    let _ = writeln!(out, "ObjectType=0x7");
    let _ = writeln!(out, "DataType=0x{:04X}", s.dtype.code());
    let _ = writeln!(out, "AccessType={}", s.access.eds());
    let _ = writeln!(out, "DefaultValue={}", default_text(index, s, node));
    let _ = writeln!(out, "PDOMapping={}", s.pdo as u8);
    let _ = writeln!(out);
}

fn object(out: &mut String, o: &Object, node: u8) {
    if o.subs.len() == 1 && o.subs[0].sub == 0 && o.kind.code() == 0x7 {
        entry(out, &format!("{:04X}", o.index), o.index, &o.subs[0], node);
        return;
    }
    let _ = writeln!(out, "[{:04X}]", o.index);
    let _ = writeln!(out, "ParameterName={}", o.name);
    let _ = writeln!(out, "ObjectType=0x{:X}", o.kind.code());
    let _ = writeln!(out, "SubNumber={}", o.subs.len());
    let _ = writeln!(out);
    for s in &o.subs {
        entry(out, &format!("{:04X}sub{:X}", o.index, s.sub), o.index, s, node);
    }
}

fn list(out: &mut String, name: &str, idx: &[u16]) {
    let _ = writeln!(out, "[{name}]");
    let _ = writeln!(out, "SupportedObjects={}", idx.len());
    for (k, i) in idx.iter().enumerate() {
        let _ = writeln!(out, "{}=0x{i:04X}", k + 1);
    }
    let _ = writeln!(out);
}

/// The EDS text of an encoder of configuration `cfg`.
pub fn write(cfg: &EncoderConfig) -> String {
    let node = cfg.node_switch;
    let d = Dictionary::encoder(cfg, node);
    let mut o = String::new();
    let _ = writeln!(o, "; Electronic data sheet of the DS 406 encoder emulated by encoder-tb (model::canopen),");
    let _ = writeln!(o, "; after the Leine & Linde CANopen Encoder Gateway application note rev. 1.3 (seed 003).");
    let _ = writeln!(o, "; Written by `tbgen eds` from the emulator's object dictionary.");
    let _ = writeln!(o);
    let _ = writeln!(o, "[FileInfo]\nFileName=encoder_ds406.eds\nFileVersion=1\nFileRevision=0\nEDSVersion=4.0\nDescription=DS 406 class 2 encoder ({:?})\nCreationTime=12:00AM\nCreationDate=01-01-2026\nCreatedBy=tbgen\nModificationTime=12:00AM\nModificationDate=01-01-2026\nModifiedBy=tbgen\n", cfg.kind);
    let _ = writeln!(o, "[DeviceInfo]\nVendorName=encoder-tb (emulated gateway)\nVendorNumber=0x{:X}\nProductName={}\nProductNumber=0x406\nRevisionNumber=0x10003\nOrderCode=", cfg.vendor_id, model::canopen::od::DEVICE_NAME);
    for r in BIT_RATES_KBPS {
        let _ = writeln!(o, "BaudRate_{r}=1");
    }
    let _ = writeln!(o, "SimpleBootUpMaster=0\nSimpleBootUpSlave=1\nGranularity=0\nDynamicChannelsSupported=0\nGroupMessaging=0\nNrOfRXPDO=0\nNrOfTXPDO=2\nLSS_Supported=0\n");
    let _ = writeln!(o, "[DummyUsage]\nDummy0001=0\nDummy0002=0\nDummy0003=0\nDummy0004=0\nDummy0005=0\nDummy0006=0\nDummy0007=0\n");
    let all: Vec<u16> = d.objects.iter().map(|o| o.index).collect();
    let mandatory = [0x1000u16, 0x1001, 0x1018];
    list(&mut o, "MandatoryObjects", &mandatory);
    let optional: Vec<u16> = all.iter().copied().filter(|i| !mandatory.contains(i) && !(0x2000..0x6000).contains(i)).collect();
    list(&mut o, "OptionalObjects", &optional);
    let manufacturer: Vec<u16> = all.iter().copied().filter(|i| (0x2000..0x6000).contains(i)).collect();
    list(&mut o, "ManufacturerObjects", &manufacturer);
    for ob in &d.objects {
        object(&mut o, ob, node);
    }
    o
}

#[cfg(test)]
mod tests {
    use super::*;
    use model::canopen::encoder::{Encoder, EncoderKind};
    use std::path::PathBuf;
    use std::process::Command;

    /// The EDS, read by the Python `canopen` library's EDS importer (an
    /// independent reader), has every object of the emulator with its name,
    /// type, access and default, and the emulator answers those defaults
    /// after power-on. Needs `.venv/` (scripts/deps.sh, `make deps`).
    #[test]
    fn eds_loads_in_python_canopen_and_matches_the_emulator() {
        let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
        let py = root.join(".venv/bin/python");
        assert!(py.exists(), "{} is missing: run scripts/deps.sh (make deps) to install the pinned Python packages", py.display());
        for (kind, node) in [(EncoderKind::Multiturn25, 0x0C), (EncoderKind::Singleturn13, 1), (EncoderKind::Linear, 127)] {
            let cfg = EncoderConfig { kind, node_switch: node, ..Default::default() };
            let dir = std::env::temp_dir().join(format!("tbgen_eds_{}_{:?}", std::process::id(), kind));
            std::fs::create_dir_all(&dir).unwrap();
            let path = dir.join("encoder.eds");
            std::fs::write(&path, write(&cfg)).unwrap();
            let script = r#"
import sys, json, canopen
od = canopen.import_od(sys.argv[1], node_id=int(sys.argv[2]))
out = []
for obj in od.values():
    subs = [obj] if isinstance(obj, canopen.objectdictionary.ODVariable) else list(obj.values())
    for v in subs:
        d = v.default
        if isinstance(d, (bytes, bytearray)):
            d = d.decode()
        out.append([obj.index, v.subindex, v.name, v.data_type, v.access_type, d])
print(json.dumps(out))
"#;
            let r = Command::new(&py).arg("-c").arg(script).arg(&path).arg(node.to_string()).output().unwrap();
            assert!(r.status.success(), "python canopen could not read the EDS: {}", String::from_utf8_lossy(&r.stderr));
            let got: Vec<(u16, u8, String, u16, String, serde_json::Value)> = serde_json::from_slice(&r.stdout).unwrap();
            let mut e = Encoder::new(&cfg).unwrap();
            e.power_on(0);
            let dict = e.dictionary().clone();
            let want: Vec<_> = dict.entries().collect();
            assert_eq!(got.len(), want.len(), "{kind:?}: entries in the EDS vs the emulator");
            for ((index, s), g) in want.iter().zip(&got) {
                assert_eq!((g.0, g.1), (*index, s.sub), "{kind:?}: order");
                let obj = dict.object(*index).unwrap();
                let name = if obj.subs.len() == 1 && s.sub == 0 { &obj.name } else { &s.name };
                assert_eq!(&g.2, name, "{index:04X}sub{}", s.sub);
                assert_eq!(g.3, s.dtype.code(), "{index:04X}sub{} type", s.sub);
                assert_eq!(g.4, s.access.eds(), "{index:04X}sub{} access", s.sub);
                let live = e.read(*index, s.sub).unwrap();
                match s.dtype {
                    DataType::VisibleString => assert_eq!(g.5.as_str().unwrap().as_bytes(), &live[..], "{index:04X}"),
                    DataType::Integer32 => assert_eq!(g.5.as_i64().unwrap(), value(&live) as i32 as i64, "{index:04X}"),
                    _ => assert_eq!(g.5.as_u64().unwrap(), value(&live) as u64, "{index:04X}sub{} default vs emulator", s.sub),
                }
            }
            std::fs::remove_dir_all(&dir).ok();
        }
    }
}
