//! The law of one pair ([`PairLaw`]: its strength and its slip law) and
//! what it lets the pair carry in force ([`limit`]).

use super::law::{Stiffness, Strength};
use super::options::SlipLaw;
use super::system::relation::Limit;

/// The law of one pair.
#[derive(Clone, Copy, Debug)]
pub struct PairLaw {
    pub strength: Strength,
    pub slip: SlipLaw,
    /// A joint that deforms ([`super::elastic`]); None: rigid.
    pub stiffness: Option<Stiffness>,
}

/// What pair `p` can carry in force, by its law and whether it is cracked.
pub(crate) fn limit(law: &PairLaw, cracked: bool, area: f64) -> Limit {
    let (_, c) = law.strength.effective(cracked);
    Limit { tension: law.strength.tensile_limit(cracked) * area, cohesion: c * area, friction: law.strength.friction }
}
