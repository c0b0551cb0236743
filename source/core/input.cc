#include <deal.II/base/utilities.h>

#include <deal.II/lac/vector.h>

#include <viscofilm/core/input.h>

#include <iostream>
#include <map>
#include <sstream>

namespace viscofilm
{
  std::string
  error_message(const std::exception &e)
  {
    if (const auto *deal_ii = dynamic_cast<const ExceptionBase *>(&e))
      {
        // One line: ParameterHandler's messages span several.
        std::ostringstream info;
        deal_ii->print_info(info);
        std::istringstream words(info.str());
        std::string        word, message;
        while (words >> word)
          message += (message.empty() ? "" : " ") + word;
        return message;
      }
    return e.what();
  }


  std::string
  to_text(const double value)
  {
    std::ostringstream text;
    text << value;
    return text.str();
  }


  void
  check_input(const bool condition, const std::string &message)
  {
    if (!condition)
      throw ExcInput(message);
  }


  template <int dim>
  Point<dim>
  parse_point(const std::string &text, const std::string &parameter)
  {
    const std::string form = dim == 2 ? "\"x, y\"" : "\"x, y, z\"";
    const std::vector<std::string> parts = Utilities::split_string_list(text, ',');
    check_input(parts.size() == dim,
                parameter + " must be a point " + form + ", got \"" + text + "\"");
    Point<dim> p;
    for (unsigned int d = 0; d < dim; ++d)
      {
        try
          {
            p[d] = Utilities::string_to_double(parts[d]);
          }
        catch (...)
          {
            check_input(false,
                        parameter + " must be a point " + form + " of " + std::to_string(dim) +
                          " numbers, got \"" + text + "\"");
          }
      }
    return p;
  }

  template <int dim>
  std::vector<Point<dim>>
  parse_point_list(const std::string &text, const std::string &parameter)
  {
    std::vector<Point<dim>> points;
    for (const std::string &item : Utilities::split_string_list(text, ';'))
      if (!item.empty())
        points.push_back(parse_point<dim>(item, parameter));
    return points;
  }


  void
  declare_function_constants(ParameterHandler &prm)
  {
    prm.declare_entry("Function constants",
                      "",
                      Patterns::Anything(),
                      "Constants usable in this subsection's expressions, as "
                      "\"name=value, name=value\". pi is always defined.");
  }


  std::string
  zero_expression(const unsigned int n_components)
  {
    std::string text = "0";
    for (unsigned int c = 1; c < n_components; ++c)
      text += "; 0";
    return text;
  }


  template <int dim>
  ParsedExpression<dim>::ParsedExpression(const unsigned int n_components)
    : n_components(n_components)
  {}


  template <int dim>
  void
  ParsedExpression<dim>::declare(ParameterHandler & prm,
                            const std::string &name,
                            const std::string &default_expression,
                            const std::string &documentation)
  {
    prm.declare_entry(name,
                      default_expression,
                      Patterns::Anything(),
                      documentation +
                        " A muparser expression in x, y (3D: x, y, z) and t "
                        "(components "
                        "separated by ';'; functions such as sin, exp, abs, "
                        "if(condition, a, b) are available).");
  }


  template <int dim>
  void
  ParsedExpression<dim>::parse(const std::string &text,
                          const std::string &constants_text,
                          const std::string &parameter)
  {
    expression = text;
    components = Utilities::split_string_list(text, ';');
    check_input(components.size() == n_components,
                parameter + " must have " + std::to_string(n_components) +
                  " component(s) separated by ';'" +
                  (n_components > 1 ? " in " + std::to_string(dim) + "D" : "") +
                  ", got " +
                  std::to_string(components.size()) + ": \"" + text + "\"");

    constants = {{"pi", numbers::PI}};
    const std::string constants_parameter =
      parameter.substr(0, parameter.rfind('/') + 1) + "Function constants";
    for (const std::string &item : Utilities::split_string_list(constants_text, ','))
      {
        const std::vector<std::string> name_value =
          Utilities::split_string_list(item, '=');
        bool valid = (name_value.size() == 2 && !name_value[0].empty());
        if (valid)
          try
            {
              constants[name_value[0]] =
                Utilities::string_to_double(name_value[1]);
            }
          catch (...)
            {
              valid = false;
            }
        check_input(valid,
                    constants_parameter +
                      " must be a list \"name=value, name=value\" of numbers, "
                      "got \"" + constants_text + "\"");
      }

    // deal.II prints muparser's diagnosis to std::cerr before it throws; the
    // message below says it once, with the parameter's name.
    std::ostringstream  muparser_diagnosis;
    std::streambuf *const cerr_buffer = std::cerr.rdbuf(muparser_diagnosis.rdbuf());
    try
      {
        parsers.clear();
        // muparser compiles lazily: evaluate once so errors surface here.
        Point<dim> inside;
        for (unsigned int d = 0; d < dim; ++d)
          inside[d] = 0.5;
        Vector<double> values(n_components);
        thread_parser().vector_value(inside, values);
        std::cerr.rdbuf(cerr_buffer);
      }
    catch (const std::exception &e)
      {
        std::cerr.rdbuf(cerr_buffer);
        parsers.clear();
        check_input(false,
                    parameter + " = \"" + text +
                      "\" is not a valid expression in " +
                      (dim == 2 ? "x, y, t" : "x, y, z, t") + " and the "
                      "constants {" + constants_text + "}: " + error_message(e));
      }
  }


  template <int dim>
  double
  ParsedExpression<dim>::value(const Point<dim> & point,
                               const double       time,
                               const unsigned int component) const
  {
    FunctionParser<dim> &parser = thread_parser();
    parser.set_time(time);
    return parser.value(point, component);
  }


  template <int dim>
  void
  ParsedExpression<dim>::vector_value(const Point<dim> &point,
                                      const double      time,
                                      Vector<double> &  values) const
  {
    FunctionParser<dim> &parser = thread_parser();
    parser.set_time(time);
    parser.vector_value(point, values);
  }


  template <int dim>
  FunctionParser<dim> &
  ParsedExpression<dim>::thread_parser() const
  {
    Assert(!components.empty(), ExcInternalError());
    std::shared_ptr<FunctionParser<dim>> &parser = parsers.get();
    if (!parser)
      {
        parser = std::make_shared<FunctionParser<dim>>(n_components);
        parser->initialize(FunctionParser<dim>::default_variable_names() + ",t",
                           components,
                           constants,
                           /*time dependent*/ true);
      }
    return *parser;
  }


  template <int dim>
  ExpressionAt<dim>
  ParsedExpression<dim>::at(const double time) const
  {
    return ExpressionAt<dim>(*this, n_components, time);
  }


  template <int dim>
  ExpressionAt<dim>::ExpressionAt(const ParsedExpression<dim> &expression,
                                  const unsigned int           n_components,
                                  const double                 time)
    : Function<dim>(n_components, time)
    , expression(expression)
  {}


  template <int dim>
  double
  ExpressionAt<dim>::value(const Point<dim> &point, const unsigned int component) const
  {
    return expression.value(point, this->get_time(), component);
  }


  template <int dim>
  void
  ExpressionAt<dim>::vector_value(const Point<dim> &point, Vector<double> &values) const
  {
    expression.vector_value(point, this->get_time(), values);
  }


  template <int dim>
  const std::string &
  ParsedExpression<dim>::text() const
  {
    return expression;
  }


  VISCOFILM_INSTANTIATE(ParsedExpression)
  VISCOFILM_INSTANTIATE(ExpressionAt)
#define INSTANTIATE(dim)                                                     \
  template Point<dim> parse_point<dim>(const std::string &, const std::string &); \
  template std::vector<Point<dim>> parse_point_list<dim>(const std::string &,     \
                                                         const std::string &);
  VISCOFILM_FOR_EACH_DIM(INSTANTIATE)
#undef INSTANTIATE
} // namespace viscofilm
