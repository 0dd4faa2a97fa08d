//! Glob matching for trace filters: `*` matches any run of characters (dots included), `?`
//! exactly one; everything else literally.

/// Whether `text` matches `pattern` as a whole.
pub fn glob_match(pattern: &str, text: &str) -> bool {
    let (p, t): (Vec<char>, Vec<char>) = (pattern.chars().collect(), text.chars().collect());
    let (mut pi, mut ti) = (0, 0);
    // Position of the last `*` and the text position it was tried at.
    let mut star: Option<(usize, usize)> = None;
    while ti < t.len() {
        // A `*` first: one in the text is matched by it, not taken literally.
        if pi < p.len() && p[pi] == '*' {
            star = Some((pi, ti));
            pi += 1;
        } else if pi < p.len() && (p[pi] == '?' || p[pi] == t[ti]) {
            pi += 1;
            ti += 1;
        } else if let Some((sp, st)) = star {
            // The last `*` takes one more character; it is then tried again from there.
            pi = sp;
            ti = st + 1;
        } else {
            return false;
        }
    }
    p[pi..].iter().all(|&c| c == '*')
}

#[cfg(test)]
mod tests {
    use super::glob_match;

    #[test]
    fn globs() {
        assert!(glob_match("tb.ba.*", "tb.ba.u0"));
        assert!(glob_match("*u0*", "tb.ba.u0_r"));
        assert!(glob_match("tb.??.u0", "tb.ba.u0"));
        assert!(!glob_match("tb.ba.u", "tb.ba.u0"));
        assert!(!glob_match("tb.?.u0", "tb.ba.u0"));
        assert!(glob_match("*", ""));
        assert!(glob_match("a*b*c", "aXXbYYbc"));
        assert!(!glob_match("a*b*c", "aXXbYYb"));
        // A `*` in the text is a character like any other.
        assert!(glob_match("*?", "*"));
        assert!(glob_match("a*", "a*b"));
        assert!(glob_match("*b", "ab*b"));
        assert!(!glob_match("*b", "ab*"));
    }
}
