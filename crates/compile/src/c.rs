//! A compiled theory printed as freestanding C99: `static const` arrays and one evaluation
//! function, no heap, no library beyond `<stdint.h>`.

use crate::tabulate::{Compiled, Domain, Form};
use std::fmt::Write;

/// A header declaring the functions and a source defining them.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CSource {
    pub header: String,
    pub source: String,
}

/// `text` as a C identifier: every other character an underscore, a leading digit prefixed.
pub fn c_identifier(text: &str) -> String {
    let mut id: String = text
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if id.is_empty() || id.starts_with(|c: char| c.is_ascii_digit()) {
        id.insert(0, 'x');
    }
    id
}

/// Text safe inside a C comment.
fn comment(text: &str) -> String {
    text.replace("*/", "* /").replace('\n', " ")
}

impl Compiled {
    /// Names of the decision variables, as the input array lists them.
    pub fn variable_names(&self) -> Vec<String> {
        match self.domain {
            Domain::Boolean => self.inputs.clone(),
            Domain::Ternary => self
                .inputs
                .iter()
                .flat_map(|i| [format!("{i} is known"), format!("{i} is true")])
                .collect(),
        }
    }

    /// The C code: `PREFIX_answer(output, in)` gives output `output`'s answer and
    /// `PREFIX_valid(in)` whether the valuation is one the reasoner accepts, where `in[v]` is
    /// decision variable `v` (non-zero for true). `prefix` must be a C identifier.
    pub fn to_c(&self, prefix: &str) -> CSource {
        let variables = self.variables();
        let functions = self.functions();
        let upper = prefix.to_ascii_uppercase();
        let mut h = String::new();
        let guard = format!("{upper}_H");
        let _ = writeln!(
            h,
            "/* Theory `{}` compiled by proclaim (generated: do not edit). */",
            comment(&self.name)
        );
        let _ = writeln!(h, "#ifndef {guard}\n#define {guard}\n");
        let _ = writeln!(h, "/* Decision variables: in[v] non-zero is true. */");
        for (v, name) in self.variable_names().iter().enumerate() {
            let _ = writeln!(h, "/*   in[{v}]: {} */", comment(name));
        }
        let _ = writeln!(h, "#define {upper}_VARIABLES {variables}");
        let _ = writeln!(h, "#define {upper}_OUTPUTS {}", self.outputs.len());
        let mut taken: Vec<String> = Vec::new();
        for (o, name) in self.outputs.iter().enumerate() {
            let mut id = format!(
                "{upper}_{}",
                c_identifier(&name.replace('~', "not_")).to_ascii_uppercase()
            );
            if taken.contains(&id) || id.ends_with("_VARIABLES") || id.ends_with("_OUTPUTS") {
                id = format!("{id}_{o}");
            }
            let _ = writeln!(h, "#define {id} {o} /* {} */", comment(name));
            taken.push(id);
        }
        let _ = writeln!(h, "\n/* Output `output`'s answer (0 or 1); 0 for an output out of range or an invalid valuation. */");
        let _ = writeln!(
            h,
            "int {prefix}_answer(unsigned output, const unsigned char in[]);"
        );
        let _ = writeln!(
            h,
            "/* Whether the valuation is one the theory's truth table holds (1) or not (0). */"
        );
        let _ = writeln!(h, "int {prefix}_valid(const unsigned char in[]);");
        let _ = writeln!(h, "\n#endif");

        let mut c = String::new();
        let _ = writeln!(
            c,
            "/* Theory `{}` compiled by proclaim (generated: do not edit). */",
            comment(&self.name)
        );
        let _ = writeln!(c, "#include <stdint.h>\n#include \"{prefix}.h\"\n");
        match self.form {
            Form::Diagram => self.diagram_c(prefix, &mut c),
            Form::Table => self.table_c(prefix, &mut c),
        }
        let _ = writeln!(c, "\nint {prefix}_valid(const unsigned char in[])\n{{\n    return {prefix}_answer({}u, in);\n}}", functions - 1);
        CSource {
            header: h,
            source: c,
        }
    }

    fn diagram_c(&self, prefix: &str, c: &mut String) {
        let d = &self.diagram;
        let index = if d.index_bytes() == 2 {
            "uint16_t"
        } else {
            "uint32_t"
        };
        let n = d.nodes.len();
        let list = |values: Vec<u32>| -> String {
            let mut text = String::new();
            for (i, v) in values.iter().enumerate() {
                if i % 16 == 0 {
                    text.push_str("\n    ");
                }
                let _ = write!(text, "{v},");
            }
            text
        };
        let _ = writeln!(c, "/* A reduced ordered decision diagram: {n} nodes (0 and 1 are false and true), {} bytes. */", self.diagram_bytes());
        let _ = writeln!(
            c,
            "static const uint8_t {prefix}_var[{n}] = {{{}\n}};",
            list(d.nodes.iter().map(|x| x.var).collect())
        );
        let _ = writeln!(
            c,
            "static const {index} {prefix}_low[{n}] = {{{}\n}};",
            list(d.nodes.iter().map(|x| x.low).collect())
        );
        let _ = writeln!(
            c,
            "static const {index} {prefix}_high[{n}] = {{{}\n}};",
            list(d.nodes.iter().map(|x| x.high).collect())
        );
        let _ = writeln!(
            c,
            "static const {index} {prefix}_root[{}] = {{{}\n}};",
            d.roots.len(),
            list(d.roots.clone())
        );
        let _ = writeln!(
            c,
            "
int {prefix}_answer(unsigned output, const unsigned char in[])
{{
    {index} node;
    if (output >= {functions}u) {{
        return 0;
    }}
    node = {prefix}_root[output];
    while (node > 1) {{
        node = in[{prefix}_var[node]] ? {prefix}_high[node] : {prefix}_low[node];
    }}
    return (int)node;
}}",
            functions = self.functions()
        );
    }

    fn table_c(&self, prefix: &str, c: &mut String) {
        let functions = self.functions();
        let variables = self.variables();
        let rows = 1usize << variables;
        let mut bytes = vec![0u8; self.table_bytes()];
        let mut assignment = vec![false; variables];
        for row in 0..rows {
            for (v, bit) in assignment.iter_mut().enumerate() {
                *bit = (row >> (variables - 1 - v)) & 1 == 1;
            }
            for f in 0..functions {
                if self.diagram.eval(self.diagram.roots[f], &assignment) {
                    let b = row * functions + f;
                    bytes[b / 8] |= 1 << (b % 8);
                }
            }
        }
        let _ = writeln!(c, "/* A truth table: bit (row * {functions} + function), {} bytes; the first variable is the row's highest bit. */", bytes.len());
        let _ = write!(
            c,
            "static const uint8_t {prefix}_table[{}] = {{",
            bytes.len()
        );
        for (i, b) in bytes.iter().enumerate() {
            if i % 16 == 0 {
                c.push_str("\n    ");
            }
            let _ = write!(c, "0x{b:02x},");
        }
        c.push_str("\n};\n");
        let row = if variables == 0 {
            "    (void)in;\n".to_string()
        } else {
            format!("    for (v = 0; v < {variables}u; v++) {{\n        bit = (bit << 1) | (in[v] ? 1u : 0u);\n    }}\n")
        };
        let declare_v = if variables == 0 {
            ""
        } else {
            "    unsigned v;\n"
        };
        let _ = writeln!(
            c,
            "
int {prefix}_answer(unsigned output, const unsigned char in[])
{{
    uint32_t bit = 0;
{declare_v}    if (output >= {functions}u) {{
        return 0;
    }}
{row}    bit = bit * {functions}u + output;
    return ({prefix}_table[bit >> 3] >> (bit & 7u)) & 1;
}}"
        );
    }
}
