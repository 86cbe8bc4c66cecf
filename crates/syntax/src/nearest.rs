//! "Did you mean …?": the known name nearest to a misspelt one.

/// The candidate equal to `name` but for case, or one edit (insert, delete, change) away; the
/// least such in sort order, so the answer does not depend on the candidates' order. Names of
/// fewer than three characters are matched by case only (every `b` is one edit from `a`).
pub fn nearest<'a>(candidates: impl IntoIterator<Item = &'a str>, name: &str) -> Option<&'a str> {
    let editable = name.chars().count() >= 3;
    candidates
        .into_iter()
        .filter(|c| {
            *c != name && (c.eq_ignore_ascii_case(name) || editable && one_edit_apart(c, name))
        })
        .min()
}

fn one_edit_apart(a: &str, b: &str) -> bool {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let (short, long) = if a.len() <= b.len() {
        (&a, &b)
    } else {
        (&b, &a)
    };
    if long.len() - short.len() > 1 {
        return false;
    }
    let prefix = short
        .iter()
        .zip(long.iter())
        .take_while(|(x, y)| x == y)
        .count();
    if short.len() == long.len() {
        short[prefix + 1.min(short.len() - prefix)..] == long[prefix + 1.min(long.len() - prefix)..]
    } else {
        short[prefix..] == long[prefix + 1..]
    }
}

#[cfg(test)]
mod tests {
    use super::nearest;

    #[test]
    fn one_edit_or_case() {
        let known = ["ballSeen", "cornerKick", "goal"];
        assert_eq!(nearest(known, "balSeen"), Some("ballSeen"));
        assert_eq!(nearest(known, "cornerkick"), Some("cornerKick"));
        assert_eq!(nearest(known, "goals"), Some("goal"));
        assert_eq!(nearest(known, "offside"), None);
        assert_eq!(nearest(known, "goal"), None);
        assert_eq!(nearest(["a"], "b"), None);
    }
}
