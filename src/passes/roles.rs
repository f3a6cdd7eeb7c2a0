//! The pipelines a frame runs, one per role of a pass, and the descriptor set of a ring slot each role writes.

use super::MAX_PASSES;
use crate::settings::MAX_FILTER_PASSES;

/// Which pipeline a pass runs, and so which descriptor set of a ring slot it uses. Filter passes 0..=2 can be
/// intermediate passes; the last filter pass runs a final pipeline, which writes the host's output. Pass 0 runs
/// the first pass's variant (step 1 from shared memory, writes the depth copy), the others the later passes' variant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Role {
    Prepare,
    Classification,
    Filter(u32),
    /// The last of two or more passes.
    FilterFinal,
    /// A single filter pass: the first pass's variant writing the output.
    FilterOnly,
    /// Intermediate later pass `n` (1..) for several lights at once (the light-slot variant).
    FilterLights(u32),
    /// The last of two or more passes for several lights at once.
    FilterLightsFinal,
}

/// The descriptor sets one record writes, one per pipeline role: every pass of the longest frame, the single
/// pass of a one-pass frame, and the later passes of several lights (intermediate ones and the final one).
pub(crate) const SETS_PER_RECORD: usize = MAX_PASSES + MAX_FILTER_PASSES as usize;

impl Role {
    /// The set of a ring slot that this role uses (its place in `roles()`).
    pub(crate) fn set_index(self) -> usize {
        match self {
            Role::Prepare => 0,
            Role::Classification => 1,
            Role::Filter(pass) => 2 + pass as usize,
            Role::FilterFinal => MAX_PASSES - 1,
            Role::FilterOnly => MAX_PASSES,
            Role::FilterLights(pass) => MAX_PASSES + pass as usize,
            Role::FilterLightsFinal => SETS_PER_RECORD - 1,
        }
    }
}

/// Every role, in set order: every filter pass but the last can be an intermediate pass, one final pass after
/// them, the single pass of a one-pass frame, then the later passes of several lights alike.
pub(crate) fn roles() -> [Role; SETS_PER_RECORD] {
    std::array::from_fn(|i| match i {
        0 => Role::Prepare,
        1 => Role::Classification,
        _ if i == MAX_PASSES - 1 => Role::FilterFinal,
        _ if i == MAX_PASSES => Role::FilterOnly,
        _ if i == SETS_PER_RECORD - 1 => Role::FilterLightsFinal,
        _ if i > MAX_PASSES => Role::FilterLights((i - MAX_PASSES) as u32),
        _ => Role::Filter(i as u32 - 2),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_role_has_its_own_set() {
        for (i, role) in roles().into_iter().enumerate() {
            assert_eq!(role.set_index(), i, "{role:?}");
        }
    }
}
