'use strict'
// eslint (flat config) for the Node side, in the style the code follows: neostandard (standard:
// two-space indent, no semicolons, single quotes). Run by tests/test_code_shape.py with the
// development packages of package.json, which users' first-run install leaves out.
const neostandard = require('neostandard')

module.exports = [
  ...neostandard({ ts: false }),
  {
    languageOptions: { sourceType: 'commonjs' },
    rules: {
      // related properties share a line here (tables of rules, event payloads): not our style
      '@stylistic/object-property-newline': 'off',
      // the rule Python's functions follow (tests/test_function_length.py): 80 lines at most
      'max-lines-per-function': ['error', { max: 80, skipBlankLines: true, skipComments: true, IIFEs: true }]
    }
  }
]
