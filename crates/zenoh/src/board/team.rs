//! A team of robots over Zenoh: each robot runs its own board, and the types its `[team]`
//! shares are also put on `proclaim/<team>/@team/<member>/<type>` (the same plain JSON and
//! attachment as on the board's own key). Every member holds the liveliness token
//! `proclaim/<team>/@team/<member>/@alive`; a member whose token goes drops out of the team's
//! values at once. What a robot hears is kept on its own replica as local types
//! (`proclaim_board::team`): `robot2.ballDistance`, `team.ballDistance` (the living members'
//! `[member, value]` pairs, its own among them) and `me`, so labels read them through the round
//! schedule's snapshot like any value.

use super::*;
use proclaim_board::team::{member_type, team_type, team_value, ME, QUORUM, SIZE};
use std::collections::BTreeMap;
use zenoh::sample::SampleKind;

/// A robot's place in its team.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Team {
    /// The team's name, the key chunk after `proclaim/`.
    pub name: String,
    /// This robot's name in the team.
    pub member: String,
    /// The types whose postings the team hears.
    pub shared: Vec<String>,
    /// How many robots the team has, if said: with it, `team.quorum` says whether this robot
    /// hears a majority of them (itself among them).
    pub size: Option<usize>,
}

/// The module the team's local types are posted by.
const TEAM_MODULE: &str = "team";

/// The team's keys.
struct TeamKeys {
    team: String,
}

impl TeamKeys {
    fn value(&self, member: &str, ty: &str) -> String {
        format!("proclaim/{}/@team/{member}/{ty}", self.team)
    }

    fn every_value(&self) -> String {
        format!("proclaim/{}/@team/*/*", self.team)
    }

    fn alive(&self, member: &str) -> String {
        format!("proclaim/{}/@team/{member}/@alive", self.team)
    }

    fn every_alive(&self) -> String {
        format!("proclaim/{}/@team/*/@alive", self.team)
    }

    /// The member and type a value's key names, or the member an `@alive` key names.
    fn parse<'k>(&self, key: &'k str) -> Option<(&'k str, &'k str)> {
        let rest = key
            .strip_prefix("proclaim/")?
            .strip_prefix(self.team.as_str())?
            .strip_prefix("/@team/")?;
        rest.split_once('/')
    }
}

/// What this robot knows of its team.
#[derive(Default)]
struct Heard {
    /// Members whose token is seen (this one always).
    alive: BTreeSet<String>,
    /// Members that have put a shared type since their token last went (this one always): a
    /// member counts towards the quorum only once it is alive and has said something, so a
    /// robot that restarts or comes back from a cut is not counted on before it is heard.
    heard_from: BTreeSet<String>,
    /// Each type's latest value from each member, in member-name order.
    values: FxHashMap<String, BTreeMap<String, Value>>,
    /// This robot's own number of its latest value of each shared type, from 1 (a put to the
    /// team carries it as its `seq`, a put again the same number).
    numbered: FxHashMap<String, u64>,
    /// The newest number heard of each (member, type), with the process that put it: a value
    /// put again late (after a newer one) is not taken for the newer. Forgotten when the member
    /// goes, so a restarted member counting from 1 again is heard.
    newest: FxHashMap<(String, String), (Option<String>, u64)>,
    /// (member, type) pairs whose member has been gone since its value came: left out of
    /// `team.<type>` until the member puts the type again, so a robot that comes back (or
    /// restarts) counts as not yet known rather than with what it said before.
    stale: FxHashSet<(String, String)>,
}

impl Heard {
    /// Whether the living members, this one among them, are more than half of a team of `size`.
    fn quorum(&self, size: usize) -> bool {
        2 * self.alive.intersection(&self.heard_from).count() > size
    }
}

/// The team part of one process on the board.
pub(crate) struct TeamPart {
    team: Team,
    keys: TeamKeys,
    heard: Mutex<Heard>,
    publishers: Mutex<FxHashMap<String, Publisher<'static>>>,
}

impl TeamPart {
    pub(crate) fn new(team: Team) -> TeamPart {
        TeamPart {
            keys: TeamKeys {
                team: team.name.clone(),
            },
            heard: Mutex::new(Heard {
                alive: BTreeSet::from([team.member.clone()]),
                heard_from: BTreeSet::from([team.member.clone()]),
                ..Heard::default()
            }),
            team,
            publishers: Mutex::default(),
        }
    }

    fn shares(&self, ty: &str) -> bool {
        self.team.shared.iter().any(|s| s == ty)
    }

    /// Whether a put of `member`'s `ty` numbered as `meta` says is newer than any heard (and
    /// now the newest). A put without a number is taken.
    fn newer(&self, member: &str, ty: &str, meta: Option<&Meta>) -> bool {
        let Some((process, seq)) = meta.and_then(|m| Some((m.process.clone(), m.seq?))) else {
            return true;
        };
        let mut heard = self.heard.lock();
        let key = (member.to_string(), ty.to_string());
        match heard.newest.get(&key) {
            Some((was, newest)) if *was == process && *newest >= seq => false,
            _ => {
                heard.newest.insert(key, (process, seq));
                true
            }
        }
    }
}

/// Joins the team: says who this robot is on its own board, follows the others' values and
/// tokens, and declares its own token last, so a teammate that hears of it can already be heard.
pub(super) async fn serve(peer: &Arc<Peer>, weak: &PeerRef) -> Result<Vec<Serving>, NetworkError> {
    let Some(part) = &peer.team else {
        return Ok(Vec::new());
    };
    let session = &peer.session;
    peer.board.post_at(
        TEAM_MODULE,
        ME,
        Value::from(part.team.member.as_str()),
        0,
        unix_now(),
        true,
    );
    if let Some(size) = part.team.size {
        let size = Value::Int(size as i64);
        peer.board
            .post_at(TEAM_MODULE, SIZE, size, 0, unix_now(), true);
    }
    peer.post_quorum(&part.heard.lock());
    let values = {
        let weak = weak.clone();
        let key = part.keys.every_value();
        session
            .declare_subscriber(key.clone())
            .allowed_origin(Locality::Remote)
            .callback(move |sample| {
                if let Some(peer) = weak.upgrade() {
                    peer.on_team_sample(&sample);
                }
            })
            .await
            .map_err(|e| NetworkError::zenoh(format!("cannot subscribe to {key}"), e))?
    };
    let members = members::follow_tokens(peer, weak, part.keys.every_alive(), |peer, key, kind| {
        let Some(part) = &peer.team else { return };
        let Some((member, _)) = part.keys.parse(key) else {
            return;
        };
        match kind {
            SampleKind::Put => peer.member_arrived(member),
            SampleKind::Delete => peer.member_gone(member),
        }
    })
    .await?;
    let alive_key = part.keys.alive(&part.team.member);
    let token = session
        .liveliness()
        .declare_token(alive_key.clone())
        .await
        .map_err(|e| NetworkError::zenoh(format!("cannot declare {alive_key}"), e))?;
    Ok(vec![
        Serving::Subscriber(values),
        Serving::Subscriber(members),
        Serving::Token(token),
    ])
}

impl Peer {
    /// This process posted `value` to `ty`: if the team shares the type, the team hears it.
    pub(super) fn share(&self, ty: &str, value: &Value, meta: &Meta) {
        let Some(part) = self.team.as_ref().filter(|p| p.shares(ty)) else {
            return;
        };
        let (_, number) = self.team_heard(&part.team.member, ty, value.clone());
        let meta = Meta {
            seq: Some(number),
            process: Some(self.me.clone()),
            ..meta.clone()
        };
        self.put_to_team(part, ty, value, &meta);
    }

    fn put_to_team(&self, part: &TeamPart, ty: &str, value: &Value, meta: &Meta) {
        let mut publishers = part.publishers.lock();
        if !publishers.contains_key(ty) {
            let key = part.keys.value(&part.team.member, ty);
            match self
                .session
                .declare_publisher(key.clone())
                .congestion_control(CongestionControl::Block)
                .encoding(Encoding::APPLICATION_JSON)
                .allowed_destination(Locality::Remote)
                .wait()
            {
                Ok(publisher) => {
                    publishers.insert(ty.to_string(), publisher);
                }
                Err(e) => {
                    tracing::error!(key, error = %e, "cannot share this type with the team");
                    return;
                }
            }
        }
        if let Some(publisher) = publishers.get(ty) {
            self.put(publisher, value, meta);
        }
    }

    fn on_team_sample(self: &Arc<Self>, sample: &zenoh::sample::Sample) {
        let Some(part) = &self.team else { return };
        let Some((member, ty)) = part.keys.parse(sample.key_expr().as_str()) else {
            return;
        };
        // Another process under this robot's own name (one restarted in its place) is not a
        // teammate.
        if member == part.team.member || ty.starts_with('@') {
            return;
        }
        let meta = sample
            .attachment()
            .and_then(|a| Meta::decode(&a.to_bytes()).ok());
        if !part.newer(member, ty, meta.as_ref()) {
            return;
        }
        if self
            .team_heard(member, ty, decode_value(&sample.payload().to_bytes()))
            .0
        {
            // The first word from a teammate that was away: it may have missed what this robot
            // put when it first heard of it (its subscription not yet known here), and this
            // robot may strike now that it counts the teammate, so the teammate must know at
            // once where this robot is.
            self.tell_the_team_again_soon();
        }
    }

    /// `member`'s latest value of `ty` is `value`: kept, and said on this replica. Says whether
    /// it is the member's first word since it last went, and for this robot's own value its
    /// number (counted under the same lock, so two posters of one type number in the order
    /// their values are kept).
    fn team_heard(&self, member: &str, ty: &str, value: Value) -> (bool, u64) {
        let Some(part) = &self.team else {
            return (false, 0);
        };
        let mut heard = part.heard.lock();
        let number = if member == part.team.member {
            let number = heard.numbered.entry(ty.to_string()).or_default();
            *number += 1;
            *number
        } else {
            0
        };
        heard
            .values
            .entry(ty.to_string())
            .or_default()
            .insert(member.to_string(), value.clone());
        let now = unix_now();
        let own = member_type(member, ty);
        self.board.post_at(TEAM_MODULE, &own, value, 0, now, true);
        if heard.stale.remove(&(member.to_string(), ty.to_string())) {
            self.board
                .post_at(TEAM_MODULE, &stale_type(&own), false.into(), 0, now, true);
        }
        self.post_team_value(&heard, ty);
        let first = heard.heard_from.insert(member.to_string());
        if first && heard.alive.contains(member) {
            self.post_quorum(&heard);
        }
        (first, number)
    }

    /// Posts `team.<ty>` on this replica: the living members' values.
    fn post_team_value(&self, heard: &Heard, ty: &str) {
        let Some(values) = heard.values.get(ty) else {
            return;
        };
        let living = values
            .iter()
            .filter(|(member, _)| {
                heard.alive.contains(*member)
                    && !heard.stale.contains(&((*member).clone(), ty.to_string()))
            })
            .map(|(member, value)| (member.as_str(), value));
        self.board.post_at(
            TEAM_MODULE,
            &team_type(ty),
            team_value(living),
            0,
            unix_now(),
            true,
        );
    }

    /// Posts `team.quorum` on this replica, for a team whose size is known.
    fn post_quorum(&self, heard: &Heard) {
        let Some(size) = self.team.as_ref().and_then(|p| p.team.size) else {
            return;
        };
        let quorum = heard.quorum(size);
        self.board
            .post_at(TEAM_MODULE, QUORUM, quorum.into(), 0, unix_now(), true);
    }

    fn member_arrived(self: &Arc<Self>, member: &str) {
        let Some(part) = &self.team else { return };
        {
            let mut heard = part.heard.lock();
            if !heard.alive.insert(member.to_string()) {
                return;
            }
            self.post_quorum(&heard);
            let types: Vec<String> = heard
                .values
                .iter()
                .filter(|(_, by)| by.contains_key(member))
                .map(|(ty, _)| ty.clone())
                .collect();
            for ty in types {
                self.post_team_value(&heard, &ty);
            }
        }
        // The newcomer has not heard this robot's values yet.
        self.tell_the_team_again_soon();
    }

    /// Puts this robot's shared values again, off Zenoh's receiving thread.
    fn tell_the_team_again_soon(self: &Arc<Self>) {
        let peer = Arc::clone(self);
        let telling = std::thread::Builder::new()
            .name("proclaim-zenoh-team".into())
            .spawn(move || peer.tell_the_team_again());
        if let Err(e) = telling {
            tracing::warn!(error = %e, "cannot tell a new teammate this robot's values");
        }
    }

    fn tell_the_team_again(&self) {
        let Some(part) = &self.team else { return };
        // Each with the number it was put with: put again after a newer value went out, it is
        // not taken for the newer.
        let own: Vec<(String, Value, u64)> = {
            let heard = part.heard.lock();
            part.team
                .shared
                .iter()
                .filter_map(|ty| {
                    let value = heard.values.get(ty)?.get(&part.team.member)?;
                    let number = heard.numbered.get(ty).copied().unwrap_or_default();
                    Some((ty.clone(), value.clone(), number))
                })
                .collect()
        };
        for (ty, value, number) in own {
            let meta = Meta {
                process: Some(self.me.clone()),
                seq: Some(number),
                ..Meta::default()
            };
            self.put_to_team(part, &ty, &value, &meta);
        }
    }

    fn member_gone(&self, member: &str) {
        let Some(part) = &self.team else { return };
        if member == part.team.member {
            return;
        }
        let mut heard = part.heard.lock();
        heard.heard_from.remove(member);
        heard.newest.retain(|(m, _), _| m != member);
        if !heard.alive.remove(member) {
            return;
        }
        tracing::info!(member, team = part.team.name, "a teammate is gone");
        self.post_quorum(&heard);
        let types: Vec<String> = heard
            .values
            .iter()
            .filter(|(_, by)| by.contains_key(member))
            .map(|(ty, _)| ty.clone())
            .collect();
        let now = unix_now();
        for ty in types {
            self.post_team_value(&heard, &ty);
            if heard.stale.insert((member.to_string(), ty.clone())) {
                let stale = stale_type(&member_type(member, &ty));
                self.board
                    .post_at(TEAM_MODULE, &stale, true.into(), 0, now, true);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn numbered(process: &str, seq: u64) -> Meta {
        Meta {
            process: Some(process.into()),
            seq: Some(seq),
            ..Meta::default()
        }
    }

    #[test]
    fn a_value_put_again_late_is_not_taken_for_a_newer_one() {
        let part = TeamPart::new(Team {
            name: "blue".into(),
            member: "robot1".into(),
            shared: vec!["vote".into()],
            size: Some(3),
        });
        assert!(part.newer("robot2", "vote", Some(&numbered("p", 2))));
        // Put again (a newcomer was told) after number 2 went out: old news.
        assert!(!part.newer("robot2", "vote", Some(&numbered("p", 1))));
        assert!(!part.newer("robot2", "vote", Some(&numbered("p", 2))));
        assert!(part.newer("robot2", "vote", Some(&numbered("p", 3))));
        // Numbers are per member and type; a restarted process counts from 1 again, and a put
        // with no number (not a proclaim process) is taken.
        assert!(part.newer("robot3", "vote", Some(&numbered("q", 1))));
        assert!(part.newer("robot2", "vote", Some(&numbered("p2", 1))));
        assert!(part.newer("robot2", "vote", None));
    }

    #[test]
    fn a_quorum_counts_members_alive_and_heard_from() {
        let mut heard = Heard {
            alive: BTreeSet::from(["robot1".to_string(), "robot2".to_string()]),
            heard_from: BTreeSet::from(["robot1".to_string()]),
            ..Heard::default()
        };
        assert!(
            !heard.quorum(3),
            "robot2 is alive but has said nothing since it came"
        );
        heard.heard_from.insert("robot2".into());
        assert!(heard.quorum(3));
        assert!(!heard.quorum(4), "two of four is no majority");
        heard.alive.remove("robot2");
        assert!(!heard.quorum(3));
    }
}
