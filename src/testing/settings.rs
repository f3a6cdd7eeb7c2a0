//! Settings by name, for the harnesses' `--set NAME=VALUE[,...]` (the viewer's `--set` does the same through
//! DnsrSettings): a setting is measured against the same build, without a rebuild.

use crate::Settings;

/// Applies `list` (`name=value` pairs separated by commas, by `Settings` field names, e.g.
/// `converged_samples=16,history_flip_samples=0`) to `s`. An unknown name, a value that does not parse as the
/// field's type, or a value out of its range is an error that names it, and leaves `s` unchanged.
pub fn apply(s: &mut Settings, list: &str) -> Result<(), String> {
    let mut next = *s;
    for item in list.split(',').filter(|i| !i.trim().is_empty()) {
        let (name, value) = item.split_once('=').ok_or_else(|| format!("\"{item}\": expected NAME=VALUE"))?;
        let (name, value) = (name.trim(), value.trim());
        macro_rules! set {
            ($($f:ident),*) => {
                match name {
                    $(stringify!($f) => next.$f = value.parse().map_err(|e| format!("{name}={value}: {e}"))?,)*
                    _ => return Err(format!("{name}: no such setting (the names are Settings' fields)")),
                }
            };
        }
        crate::settings::for_each_setting!(set);
    }
    next.validate().map_err(|e| e.to_string())?;
    *s = next;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::apply;
    use crate::Settings;

    #[test]
    fn sets_by_field_name_and_refuses_what_it_cannot_set() {
        let mut s = Settings::default();
        apply(&mut s, "converged_samples=16, history_flip_samples=0,filter_passes=3").unwrap();
        assert_eq!((s.converged_samples, s.history_flip_samples, s.filter_passes), (16.0, 0.0, 3));
        let before = s;
        for bad in ["no_such_setting=1", "filter_passes=2.5", "filter_passes=9", "converged_samples=nan", "converged_samples"] {
            let e = apply(&mut s, &format!("min_current_weight=0.5,{bad}")).unwrap_err();
            assert!(e.contains(bad.split('=').next().unwrap()), "{bad}: {e}");
            assert_eq!(s, before, "{bad} left the settings changed");
        }
    }
}
