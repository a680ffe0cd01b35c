//! The values of options written as lists: numbers (`0,0.5,1`, fractions `5/17`) and
//! non-negative integers (`2,2,1`).

use anyhow::Result;

use crate::exit::{bad_input, BadInput};

/// Parses a number list argument (`0,0.5,1`; fractions `5/17` allowed).
pub(crate) fn numbers(text: &str, what: &str) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    for (i, s) in text
        .split([',', ' '])
        .filter(|s| !s.trim().is_empty())
        .enumerate()
    {
        let s = s.trim();
        let v = if let Some((a, b)) = s.split_once('/') {
            let parsed = (a.trim().parse::<f64>(), b.trim().parse::<f64>());
            match parsed {
                (Ok(a), Ok(b)) if b != 0.0 => Some(a / b),
                _ => None,
            }
        } else {
            s.parse::<f64>().ok()
        };
        match v.filter(|v| v.is_finite()) {
            Some(v) => out.push(v),
            None => {
                return bad_input(format!(
                    "{what}: value {} is \"{s}\", not a finite number (write e.g. 0.5 or 5/17)",
                    i + 1
                ))
            }
        }
    }
    if out.is_empty() {
        return bad_input(format!("{what}: no numbers given"));
    }
    Ok(out)
}

/// Parses a list of non-negative integers (`2,2,1`).
pub(crate) fn integers(text: &str, what: &str) -> Result<Vec<usize>> {
    text.split([',', ' '])
        .filter(|s| !s.trim().is_empty())
        .enumerate()
        .map(|(i, s)| {
            s.trim().parse::<usize>().map_err(|_| {
                BadInput(format!(
                    "{what}: value {} is \"{}\", not a non-negative integer",
                    i + 1,
                    s.trim()
                ))
                .into()
            })
        })
        .collect()
}

/// Parses `NUxNV` (e.g. `4x3`).
pub(crate) fn net_size(text: &str, what: &str) -> Result<(usize, usize)> {
    let parsed = text
        .split_once(['x', 'X', '×'])
        .and_then(|(a, b)| Some((a.trim().parse().ok()?, b.trim().parse().ok()?)));
    match parsed {
        Some((a, b)) => Ok((a, b)),
        None => bad_input(format!(
            "{what}: \"{text}\" is not a grid size; write rows x columns, e.g. 4x3"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::exit::{exit_code, EXIT_BAD_INPUT};

    #[test]
    fn number_lists() {
        assert_eq!(
            numbers("0, 5/17 1", "p").unwrap(),
            vec![0.0, 5.0 / 17.0, 1.0]
        );
        let e = numbers("0,x", "--params").unwrap_err();
        assert_eq!(exit_code(&e), EXIT_BAD_INPUT);
        assert!(e.to_string().contains("--params: value 2 is \"x\""), "{e}");
        assert!(numbers("1/0", "p").is_err());
        assert_eq!(integers("2,1", "c").unwrap(), vec![2, 1]);
        assert!(integers("-1", "c").is_err());
    }
}
